"""cablestudy/dynamics/body_rates.py: the global rotation vector of small changes of a
body's Euler angles (R = Rz(yaw) Ry(pitch) Rx(roll))."""

from __future__ import annotations

import numpy as np
import pytest

from cablestudy.dynamics.body_rates import euler_rate_matrix, rotation_vector
from tests.system_contract import _rotation


@pytest.mark.parametrize(
    "angles", [(0.0, 0.0, 0.0), (0.3, -0.2, 0.7), (-1.2, 1.1, 2.5), (0.0, 0.0, np.pi / 2)]
)
def test_the_rate_matrix_is_the_derivative_of_the_rotation(angles: tuple) -> None:
    """Each column of E is the axial vector of dR/d(angle) R^T, by central differences
    (step 1e-6: truncation 1e-12, rounding 1e-10 of the unit entries; bar 1e-8)."""
    a = np.array(angles)
    E = euler_rate_matrix(a)
    R = _rotation(a)
    h = 1e-6
    for k in range(3):
        d = np.zeros(3)
        d[k] = h
        W = (_rotation(a + d) - _rotation(a - d)) / (2.0 * h) @ R.T
        w = np.array([W[2, 1], W[0, 2], W[1, 0]])
        np.testing.assert_allclose(W, -W.T, atol=1e-8)  # a rotation rate: skew
        np.testing.assert_allclose(E[:, k], w, atol=1e-8)


def test_zero_angles_leave_the_changes_as_they_are() -> None:
    changes = np.array([0.1 + 0.2j, -0.3j, 0.05])
    assert rotation_vector(np.zeros(3), changes) is changes
    yawed = rotation_vector(np.array([0.0, 0.0, np.pi / 2]), np.array([0.0, 1.0, 0.0]))
    np.testing.assert_allclose(yawed, [-1.0, 0.0, 0.0], atol=1e-15)  # pitch about -x
