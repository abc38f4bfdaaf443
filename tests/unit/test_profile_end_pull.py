"""profile_quantities' end tangents (cablestudy/physics/profile.py): the end tension's
direction where given, the one-sided differences where it is zero or held back, NaN
where it is not finite (a failed case)."""

from __future__ import annotations

import numpy as np

from cablestudy.physics.profile import end_pulls, profile_quantities


def _arc(n: int) -> tuple[np.ndarray, np.ndarray]:
    # a quarter circle of radius 1 from (1, 0, 0) up to (0, 0, 1): tangent at s is
    # (-sin s, 0, cos s), elevation pi/2 - s where the horizontal part points to -x
    s = np.linspace(0.0, np.pi / 2, n)
    return s, np.stack([np.cos(s), 0.0 * s, np.sin(s)], axis=-1)


def _angles(s: np.ndarray, r: np.ndarray, pull: np.ndarray | None) -> np.ndarray:
    out = profile_quantities(
        s,
        r,
        np.ones(r.shape[:-1]),
        axial_stiffness=np.ones(s.size),
        area=np.zeros(s.size),
        density=1025.0,
        gravity=9.81,
        end_pull=pull,
    )
    return out["elevation"]


def test_the_end_pull_gives_the_end_angle_and_zero_keeps_the_difference() -> None:
    s, r = _arc(5)
    plain = _angles(s, r, None)
    # the exact tangents at the ends, scaled (only the direction counts)
    pull = np.array([[0.0, 0.0, 3.0], [-2.0, 0.0, 2.0e-17]])
    got = _angles(s, r, pull)
    assert got[0] == np.pi / 2 and abs(got[-1]) < 1e-16
    np.testing.assert_array_equal(got[1:-1], plain[1:-1])  # the interior as before
    # a zero vector (held back, or no tension) keeps the one-sided difference
    half = _angles(s, r, np.array([[0.0, 0.0, 3.0], [0.0, 0.0, 0.0]]))
    assert half[0] == np.pi / 2 and half[-1] == plain[-1]
    # non-finite: a failed case's angles are NaN at that end
    bad = _angles(s, r, np.array([[np.nan] * 3, [0.0, 0.0, 0.0]]))
    assert np.isnan(bad[0]) and bad[-1] == plain[-1]


def test_end_pulls_signs_and_what_they_hold_back() -> None:
    fa, fb = np.array([1.0, 0.0, -2.0]), np.array([-1.0, 0.0, -3.0])
    got = end_pulls(fa, fb, free_a=True, free_b=True)
    np.testing.assert_array_equal(got, [[1.0, 0.0, -2.0], [1.0, 0.0, 3.0]])  # T(0), T(L)
    held = end_pulls(fa, fb, free_a=False, free_b=True, floor=2.5)  # |force_a| < floor
    np.testing.assert_array_equal(held, [[0.0, 0.0, 0.0], [1.0, 0.0, 3.0]])
    # many cases: per case flags and floors
    many = end_pulls(
        np.stack([fa, fa]),
        np.stack([fb, fb]),
        free_a=np.array([True, False]),
        free_b=True,
        floor=np.array([0.0, 10.0]),
    )
    np.testing.assert_array_equal(many[0], got)
    np.testing.assert_array_equal(many[1], np.zeros((2, 3)))
