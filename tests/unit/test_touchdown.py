"""The touchdown point from node heights (cablestudy.physics.seabed)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from cablestudy.physics.seabed import touchdown_arc_length

S = np.linspace(0.0, 100.0, 41)  # node spacing h = 2.5 m


def _parabola(s_td: float, *, c: float = 0.01, level: float = 0.0) -> np.ndarray:
    return level + c * np.clip(S - s_td, 0.0, None) ** 2


@pytest.mark.parametrize("s_td", [20.0, 21.3, 37.499, 61.0])
def test_a_parabola_leaving_the_seabed_is_found_exactly(s_td: float) -> None:
    # laid from A, rising as the square of the distance: sqrt(height) is linear in s
    z = -50.0 + _parabola(s_td)
    assert touchdown_arc_length(S, z, -50.0, 1e-9) == pytest.approx(s_td, abs=1e-9)


def test_mirrored_line_touches_down_at_the_mirrored_point() -> None:
    # the same line hanging from A down to a laid part at B
    z = _parabola(21.3)[::-1]
    assert touchdown_arc_length(S, z, 0.0, 1e-9) == pytest.approx(100.0 - 21.3, abs=1e-9)


def test_penetration_and_a_sloped_seabed() -> None:
    # a penalty seabed: the laid nodes sink by 2 mm; the seabed rises 5 % along s
    bed = -30.0 + 0.05 * S
    z = bed + _parabola(43.7, level=-0.002)
    assert touchdown_arc_length(S, z, bed, 1e-6) == pytest.approx(43.7, abs=1e-9)


def test_a_catenary_within_the_interpolation_error() -> None:
    a = 40.0  # catenary parameter [m]: height sqrt(a^2 + u^2) - a at distance u
    h = float(S[1] - S[0])
    for s_td in (10.0, 31.2, 55.55):
        u = np.clip(S - s_td, 0.0, None)
        z = np.sqrt(a**2 + u**2) - a
        err = touchdown_arc_length(S, z, 0.0, 1e-9) - s_td
        # bound derived in the docstring: 3 h^3 / (4 a^2) = 7.3e-3 m here
        assert abs(err) <= 3.0 * h**3 / (4.0 * a**2), err
        # and it is far better than the node spacing a nearest-node answer would give
        assert abs(err) < 0.01 * h


def test_no_contact_or_no_suspended_span_is_nan() -> None:
    assert math.isnan(touchdown_arc_length(S, np.full(S.size, -10.0), -20.0, 1e-6))
    assert math.isnan(touchdown_arc_length(S, np.full(S.size, -20.0), -20.0, 1e-6))


def test_one_suspended_node_falls_back_to_linear_interpolation() -> None:
    z = np.zeros(S.size)
    z[-1] = 1.0  # only the end node is lifted: the gap reaches tol = 0.25 a quarter of the way
    assert touchdown_arc_length(S, z, 0.0, 0.25) == pytest.approx(S[-2] + 0.25 * 2.5)


def test_a_buoyant_piece_on_a_laid_leg_is_named_in_the_failure() -> None:
    """Issue 23's new-user trial: a chain-polyester-chain leg whose polyester (8 kg/m,
    0.16 m: about -124 N/m in water) is lighter than water. The seabed-contact model
    cannot lay it; the message must say so, not that the line is longer than its path
    (750 m against 785 m here)."""
    from cablestudy.statics import STATIC_SOLVERS
    from cablestudy.study.loader import parse_study_text, validate_data
    from cablestudy.study.problem import static_problem

    text = """\
name: leg
environment: {fluid: water, depth: 150.0, seabed: {friction: 0.5}}
line:
  segments:
    - {length: 300.0, diameter: 0.151, mass_per_length: 141.0, axial_stiffness: 6.0e8}
    - {length: 400.0, diameter: 0.16, mass_per_length: 8.0, axial_stiffness: 1.0e8}
    - {length: 50.0, diameter: 0.151, mass_per_length: 141.0, axial_stiffness: 6.0e8}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -150.0]}
  b: {kind: fixed, position: [650.0, 0.0, -15.0]}
"""
    src = parse_study_text(text, "leg.yaml")
    res = STATIC_SOLVERS["catenary"].solve(static_problem(validate_data(src.data, src)))
    assert res.status != 0
    assert "buoyant piece" in res.message and "s = 300 to 700 m" in res.message, res.message
    assert "longer than the straight path" not in res.message
