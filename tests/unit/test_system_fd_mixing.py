"""The damped Anderson mixing of the system frequency domain's drag iteration
(cablestudy.dynamics.system_fd_fit.anderson, ``DEPTH`` 4, ``MIXING`` 0.8; issue 24's
speed work) still stops at the fixed point of the equivalent linearisation, not merely
where its steps became small: a damped step is shorter than the undamped one, so a
stop on the velocity change could in principle come early.

The oracle is the same case iterated to ``tolerance`` 1e-9 (a thousandth of the bar
below; 1e-12 is below what the iteration reaches where rounding and the drag's kink at
zero velocity leave changes of about 1e-10: heave at 0.5 Hz stops at 7e-10). At the
default 1e-6 the distance to it is the last change times ``rho / (1 - rho)``, ``rho``
the contraction of the mixed iteration near the fixed point: measured on case8 (surge,
heave, sway, pitch, 0.02-0.5 Hz, 20 elements) the answers lie within 4.7e-7 of the
largest value, as with the undamped mixing of depth 3 before (4.5e-7); the bar is the
tolerance itself, 1e-6, which a mixing that stopped on short steps away from the fixed
point would exceed (with ``MIXING`` 0.05 seven of the nine cases here fail, by up to
1.9e-5).
"""

from __future__ import annotations

import numpy as np
import pytest

from cablestudy.dynamics.frequency_model import DragSettings
from tests.system_frequency_reference import solve_system_harmonic
from tests.unit.test_system_fd_kernel import _case8_model

#: the drag iteration's default tolerance on the velocity change (module docstring)
BAR = 1e-6


@pytest.fixture(scope="module")
def case8() -> object:
    return _case8_model(11)


@pytest.mark.parametrize("dof", [0, 2, 4])
@pytest.mark.parametrize("frequency", [0.05, 0.25, 0.5])
def test_mixed_iteration_stops_at_the_fixed_point(
    case8: object, dof: int, frequency: float
) -> None:
    X = np.zeros((1, 6), dtype=complex)
    X[0, dof] = -2j if dof < 3 else -0.05j
    w = 2.0 * np.pi * frequency
    got = solve_system_harmonic(case8, w, X)
    tight = solve_system_harmonic(case8, w, X, DragSettings(tolerance=1e-9))
    assert got.status == tight.status == 0, (got.message, tight.message)
    assert got.iterations < tight.iterations
    for a, b in (
        (got.end_force, tight.end_force),
        (got.point_displacement, tight.point_displacement),
        (np.concatenate(got.displacement), np.concatenate(tight.displacement)),
        (np.concatenate(got.element_tension), np.concatenate(tight.element_tension)),
    ):
        big = np.abs(b).max()
        assert big > 0.0
        np.testing.assert_allclose(a, b, rtol=0, atol=BAR * big)
