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


LEG = """\
name: leg
environment: {fluid: water, depth: 150.0, seabed: {friction: 0.5}}
line:
  segments:
    - {length: 300.0, diameter: 0.151, mass_per_length: 141.0, axial_stiffness: 6.0e8}
    - {length: 400.0, diameter: 0.16, mass_per_length: 8.0, axial_stiffness: 1.0e8}
    - {length: 50.0, diameter: 0.151, mass_per_length: 141.0, axial_stiffness: 6.0e8}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -150.0]}
  b: {kind: fixed, position: [SPAN, 0.0, -15.0]}
"""


def _leg(span: float, method: str):  # type: ignore[no-untyped-def]
    from dataclasses import replace

    from cablestudy.config.loader import parse_study_text, validate_data
    from cablestudy.problem import static_problem
    from cablestudy.statics import STATIC_SOLVERS

    src = parse_study_text(LEG.replace("SPAN", f"{span:.1f}"), "leg.yaml")
    problem = replace(static_problem(validate_data(src.data, src)), n_nodes=31)
    return STATIC_SOLVERS[method].solve(problem)


def test_a_buoyant_piece_on_a_laid_leg_is_named_in_the_failure() -> None:
    """Issue 23's new-user trial: a chain-polyester-chain leg whose polyester (8 kg/m,
    0.16 m: about -124 N/m in water) is lighter than water, its fairlead 500 m out. The
    seabed-contact model cannot lay the polyester; the message must say so, not that
    the line is longer than its path (750 m against 635 m here: the buoyant piece can
    hold a longer line off the seabed, so that would be no reason)."""
    res = _leg(500.0, "catenary")
    assert res.status != 0
    assert "buoyant piece" in res.message and "s = 300 to 700 m" in res.message, res.message
    assert "longer than the" not in res.message


def test_a_buoyant_piece_beside_a_laid_leg_rises_as_a_lazy_wave() -> None:
    """The same leg with its fairlead 650 m out: the chain lies on the seabed from the
    anchor and the polyester arches up (a lazy wave; the touchdown guess keeps it off
    the seabed). The catenary's answer is verified (status 0) and agrees with the
    discrete model's to that model's resolution, one element's weight in water (30
    elements of 25 m of chain: (141 - rho pi/4 0.151^2) g 25 m = 30 kN). The arch rises
    about 20 m above z = 0: cablestudy's fluid has no surface (nothing checks it)."""
    cable, lumped = _leg(650.0, "catenary"), _leg(650.0, "discrete")
    assert cable.status == 0 and lumped.status == 0, (cable.message, lumped.message)
    assert 0.0 < cable.laid_length < 300.0  # the chain only: the polyester is lifted
    element = (141.0 - 1025.0 * math.pi / 4.0 * 0.151**2) * 9.80665 * 25.0
    np.testing.assert_allclose(cable.force_b, lumped.force_b, rtol=0, atol=element)
    np.testing.assert_allclose(cable.force_a, lumped.force_a, rtol=0, atol=element)
