"""A line between fixed ends on one vertical (cablestudy.statics.vertical): the
catenary's degenerate case, where the horizontal tension is zero. Taut: the elastic
bar's closed form. Folded (longer than the ends' distance, stretched): the limit of the
general catenary as the ends' horizontal offset goes to zero, and the whole line's
balance. The peer file that needed it (MoorDyn's pinnedBody.txt, line 1) now solves."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from cablestudy.statics import STATIC_SOLVERS, EndCondition, Medium, StaticProblem
from cablestudy.statics.vertical import solve_vertical
from tests.line_models import one_segment

W, L, EA = 500.0, 100.0, 1e7  # weight in the fluid [N/m], length [m], EA [N]
LINE = one_segment(length=L, weight=W, mass=60.0, axial_stiffness=EA)


def _problem(drop: float, offset: float = 0.0) -> StaticProblem:
    """End A at the origin, end B ``drop`` [m] below it and ``offset`` [m] aside."""
    return StaticProblem(
        line=LINE,
        medium=Medium(density=0.0, gravity=9.81),
        end_a=EndCondition(kind="fixed", position=np.zeros(3)),
        end_b=EndCondition(kind="fixed", position=np.array([offset, 0.0, -drop])),
        n_nodes=21,
        tolerance=1e-12,
    )


@pytest.mark.parametrize("stretch", [0.5, 1.0])
def test_taut_vertical_line_is_the_elastic_bar(stretch: float) -> None:
    """B hangs below A farther than the line reaches alone: T_B = EA (D - L) / L -
    W L / 2 (the mean tension W L / 2 stretches it by W L^2 / (2 EA)), T_A = T_B + W L."""
    res = STATIC_SOLVERS["catenary"].solve(_problem(L + stretch))
    assert res.status == 0, res.message
    t_b = EA * stretch / L - W * L / 2.0
    np.testing.assert_allclose(res.force_b, [0.0, 0.0, t_b], rtol=1e-12, atol=1e-9 * W * L)
    np.testing.assert_allclose(res.force_a, [0.0, 0.0, -(t_b + W * L)], rtol=1e-12)


@pytest.mark.parametrize("drop", [-99.0, -60.0, 1e-9, 60.0, 99.0])
def test_folded_vertical_line_is_the_limit_of_the_catenary(drop: float) -> None:
    """Ends on one vertical closer than the line's length: each end carries the weight
    of its leg down to the fold. The general catenary with the ends 0.1 mm apart
    horizontally gives the same vertical forces to O(offset / L) = 1e-6 of the weight
    (measured 1e-10), and both balance the whole weight to round-off."""
    exact = solve_vertical(_problem(drop), np.linspace(0.0, L, 21))
    assert exact is not None
    near = STATIC_SOLVERS["catenary"].solve(_problem(drop, offset=1e-4))
    assert near.status == 0, near.message
    weight = W * L
    np.testing.assert_allclose(exact.force_a[2], near.force_a[2], rtol=0, atol=1e-6 * weight)
    np.testing.assert_allclose(exact.force_b[2], near.force_b[2], rtol=0, atol=1e-6 * weight)
    total = exact.force_a + exact.force_b
    np.testing.assert_allclose(total, [0.0, 0.0, -weight], rtol=1e-14)
    # the registry's solver takes it, verified (status 0), with the ends where put
    res = STATIC_SOLVERS["catenary"].solve(_problem(drop))
    assert res.status == 0, res.message
    np.testing.assert_allclose(res.position[-1], [0.0, 0.0, -drop], atol=1e-12 * L)
    # the fold (zero tension) lies within a sample interval: the smallest sampled
    # tension is at most one interval's weight, W L / 20
    assert float(np.min(res.tension)) <= W * L / 20.0


def test_the_peer_file_with_a_vertical_line_now_solves() -> None:
    """MoorDyn's pinnedBody.txt line 1: 5 m hanging in vacuum between points exactly
    5 m apart on one vertical (a line search failure before): stretched by its weight,
    it folds by a fraction of a millimetre below B, which carries that leg's weight."""
    from cablestudy.analyses.static import solve_static
    from cablestudy.interchange import import_model, imported_yaml
    from cablestudy.study import parse_study_text
    from cablestudy.study.grid import expand_cases

    rel = "moordyn/tests/Mooring/body_tests/pinnedBody.txt"
    path = Path(__file__).parents[1] / "data" / rel
    imported = import_model(path.read_text(), rel, lines=[1], folder=path.parent)
    _, cases = expand_cases(parse_study_text(imported_yaml(imported, rel), "<i>"))
    res = solve_static(cases[0], None)
    assert res.status == 0, res.message
    seg = cases[0].study.line.segments[0]
    weight = seg.mass_per_length * 9.80665 * 5.0  # vacuum
    np.testing.assert_allclose(res.force_a + res.force_b, [0.0, 0.0, -weight], rtol=1e-12)
    assert 0.0 < -res.force_b[2] < 1e-3 * weight
