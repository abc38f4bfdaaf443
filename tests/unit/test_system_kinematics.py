"""The driven points of a system follow the exact rigid-body motion of their body
(rotation R = Rz(yaw) Ry(pitch) Rx(roll) of cablestudy.statics.system, any angle), with
velocity and acceleration its exact time derivatives."""

from __future__ import annotations

import math

import numpy as np

from cablestudy.dynamics.system_kernels import drives_at
from cablestudy.dynamics.system_model import SlotMotion
from cablestudy.statics.system import rotation

BASE = np.array([[3.0, -2.0, 1.0, 0.1, -0.2, 0.3]])  # a body already offset and turned
OFFSET = np.array([[20.0, -5.0, -15.0], [0.0, 0.0, 0.0]])
#: surge 2 m at 0.07 Hz, pitch 0.3 rad at 0.05 Hz, yaw 0.5 rad at 0.03 Hz (large angles)
HARMONICS = [(0, 0, 2.0, 0.07, 0.4), (1, 1, 0.3, 0.05, 0.0), (1, 2, 0.5, 0.03, 1.1)]


def _motion() -> tuple:
    return SlotMotion(
        slot=np.array([s for s, *_ in HARMONICS]),
        direction=np.array([np.eye(3)[k] for _, k, *_ in HARMONICS]),
        amplitude=np.array([h[2] for h in HARMONICS]),
        frequency=np.array([h[3] for h in HARMONICS]),
        phase=np.array([h[4] for h in HARMONICS]),
    ).kernel_args()


def _pose(t: float) -> tuple[np.ndarray, np.ndarray]:
    """Reference point and angles of the body at ``t``, written out by hand."""
    q = BASE[0].copy()
    for slot, k, amp, f, ph in HARMONICS:
        q[3 * slot + k] += amp * math.sin(2.0 * math.pi * f * t + ph)
    return q[:3], q[3:]


def _drives(t: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    R0 = rotation(BASE[0, 3:])[None]
    static = BASE[0, :3] + OFFSET @ R0[0].T
    dx, dv, da = (np.zeros((2, 3)) for _ in range(3))
    bx, bR = np.zeros((1, 3)), np.zeros((1, 3, 3))
    drives_at(
        t, _motion(), BASE, R0, np.array([0, 0]), np.array([-1, -1]), OFFSET, static,
        dx, dv, da, bx, bR,
    )  # fmt: skip
    return dx, dv, da


def test_a_body_point_moves_by_the_exact_rotation() -> None:
    """Position X(t) + R(theta(t)) p at any time, to rounding (positions of tens of
    metres: 1e-12 m is a few hundred ulp), and the reference point (p = 0) with X."""
    for t in np.linspace(0.0, 40.0, 17):
        x, theta = _pose(t)
        dx, _, _ = _drives(t)
        np.testing.assert_allclose(dx[0], x + rotation(theta) @ OFFSET[0], rtol=0, atol=1e-12)
        np.testing.assert_allclose(dx[1], x, rtol=0, atol=1e-12)
    # not small-angle: at the largest yaw the exact point is metres from the point turned
    # by the angle changes taken as a small rotation vector
    t = (0.25 / 0.03 - 1.1 / (2.0 * math.pi * 0.03)) % (1.0 / 0.03)
    x, theta = _pose(t)
    lin = x + (rotation(BASE[0, 3:]) @ OFFSET[0]) + np.cross(theta - BASE[0, 3:], OFFSET[0])
    assert np.linalg.norm(_drives(t)[0][0] - lin) > 1.0


def test_velocity_and_acceleration_are_the_derivatives_of_the_position() -> None:
    """Central differences of the position with step h = 1e-3 s. Truncation: h^2/6
    times the third derivative for the velocity, h^2/12 times the fourth for the
    acceleration; those derivatives are at most |p| (sum of the angles' A w)^3 and ^4
    plus the surge's A w^3 and A w^4, below 1 m/s^3 and 1 m/s^4 here: under 2e-7 m/s
    and 1e-7 m/s^2. Rounding: 1e-12 m / h = 1e-9 m/s and 4e-12 m / h^2 = 4e-6 m/s^2.
    So 1e-6 m/s and 1e-5 m/s^2 bound both."""
    h = 1e-3
    for t in (3.0, 11.7, 25.2):
        xm, x0, xp = (_drives(t + d)[0] for d in (-h, 0.0, h))
        _, v, a = _drives(t)
        np.testing.assert_allclose(v, (xp - xm) / (2 * h), rtol=0, atol=1e-6)
        np.testing.assert_allclose(a, (xp - 2 * x0 + xm) / h**2, rtol=0, atol=1e-5)


def test_a_translating_body_moves_its_points_by_exactly_its_displacement() -> None:
    """No rotation motion: (R - R0) p is exactly zero, so a point moves by the surge
    alone, bit for bit (what lets a system of one line equal the one-line study)."""
    R0 = rotation(BASE[0, 3:])[None]
    static = BASE[0, :3] + OFFSET @ R0[0].T
    dx, dv, da = (np.zeros((2, 3)) for _ in range(3))
    bx, bR = np.zeros((1, 3)), np.zeros((1, 3, 3))
    surge = SlotMotion(
        slot=np.array([0]), direction=np.array([[1.0, 0.0, 0.0]]), amplitude=np.array([2.0]),
        frequency=np.array([0.1]), phase=np.array([0.0]),
    ).kernel_args()  # fmt: skip
    drives_at(2.0, surge, BASE, R0, np.array([0, 0]), np.array([-1, -1]), OFFSET, static,
              dx, dv, da, bx, bR)  # fmt: skip
    s = 2.0 * math.sin(2.0 * math.pi * 0.1 * 2.0)
    np.testing.assert_array_equal(dx[:, 0], static[:, 0] + s)
    np.testing.assert_array_equal(dx[:, 1:], static[:, 1:])
