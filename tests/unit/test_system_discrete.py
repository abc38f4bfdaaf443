"""Systems solved by method discrete (lines with bending stiffness EI): each line's end
stiffness condensed from the discrete model's tangent against central differences, the
catenary answer recovered at order two as the mesh is refined when EI = 0, and
convergence under refinement with EI (which changes the answer: it is used)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from cablestudy.analyses.system import system_model
from cablestudy.statics import STATIC_SOLVERS, EndCondition
from cablestudy.statics.line_stiffness import line_end_stiffness
from cablestudy.statics.system_methods import solve_system_by
from cablestudy.statics.system_model import SystemResult
from cablestudy.study import parse_study_text
from cablestudy.study.grid import expand_cases
from cablestudy.study.loader import StudyError
from tests.system_models import polyester

SEG = "{length: %s, diameter: 0.1, mass_per_length: 20.0, axial_stiffness: 5.0e8%s}"


def hanging_system(method: str, nodes: int, extra: str = "") -> str:
    """Three legs from anchors in mid-water (no seabed) to a clump, a riser from the
    clump to a body's fairlead: every line hangs free, so the discrete model's error is
    its mesh error alone (no touchdown at a node)."""
    return f"""\
name: hang
environment: {{fluid: water}}
points:
  anchor1: {{kind: fixed, position: [-150.0, 0.0, -100.0]}}
  anchor2: {{kind: fixed, position: [75.0, 129.9, -100.0]}}
  anchor3: {{kind: fixed, position: [75.0, -129.9, -100.0]}}
  clump: {{kind: free, position: [3.0, 1.0, -65.0], mass: 2000.0}}
  fair: {{kind: body, body: buoy, offset: [0.0, 0.0, -10.0]}}
bodies:
  buoy: {{kind: prescribed, position: [5.0, 2.0, 0.0, 0.0, 0.0, 0.0]}}
lines:
  leg1: {{a: anchor1, b: clump, segments: [{SEG % (170.0, extra)}]}}
  leg2: {{a: anchor2, b: clump, segments: [{SEG % (170.0, extra)}]}}
  leg3: {{a: anchor3, b: clump, segments: [{SEG % (170.0, extra)}]}}
  riser: {{a: clump, b: fair, segments: [{SEG % (55.0, extra)}]}}
analysis:
  static: {{method: {method}, nodes: {nodes}, tolerance: 1.0e-11}}
"""


def _solve(text: str) -> SystemResult:
    _, cases = expand_cases(parse_study_text(text, "hang.yaml"))
    study = cases[0].study
    res = solve_system_by(system_model(study), study.analysis.static.method, STATIC_SOLVERS)
    assert res.status == 0, res.message
    return res


def _numbers(res: SystemResult) -> np.ndarray:
    """End tensions [N], the clump's position [m] and the body's translational
    stiffness [N/m], scaled to comparable sizes (tension / 1e4, stiffness / 1e2)."""
    tension = [np.linalg.norm(r.force_a) for r in res.lines] + [
        np.linalg.norm(r.force_b) for r in res.lines
    ]
    return np.concatenate(
        (
            np.array(tension) / 1e4,
            res.point_position[3],
            res.body_stiffness[0, :3, :3].ravel() / 1e2,
        )
    )


def _discrete(problem, ra, rb):  # type: ignore[no-untyped-def]
    res = STATIC_SOLVERS["discrete"].solve(
        replace(
            problem,
            end_a=EndCondition(kind="fixed", position=np.asarray(ra, dtype=float)),
            end_b=EndCondition(kind="fixed", position=np.asarray(rb, dtype=float)),
        )
    )
    assert res.status == 0, res.message
    return res


def test_discrete_end_stiffness_is_the_central_difference() -> None:
    """K = -d f / d r of a bending line (EI = 2e5 N m^2, 40 elements, pinned ends as
    every system line is): the condensed tangent, with the bending energy's full
    Hessian, against central differences."""
    base = polyester(100.0, depth=None)
    problem = replace(
        base,
        line=replace(base.line, bending_stiffness=np.array([2e5])),
        n_nodes=41,
    )
    ra, rb = np.zeros(3), np.array([80.0, 10.0, -30.0])
    res = _discrete(problem, ra, rb)
    K = line_end_stiffness(
        replace(
            problem,
            end_a=EndCondition(kind="fixed", position=ra),
            end_b=EndCondition(kind="fixed", position=rb),
        ),
        res,
    )
    h = 1e-3
    Kfd = np.empty_like(K)
    for j in range(2):
        for c in range(3):
            step = np.zeros((2, 3))
            step[j, c] = h
            plus = _discrete(problem, ra + step[0], rb + step[1])
            minus = _discrete(problem, ra - step[0], rb - step[1])
            Kfd[0, j, :, c] = -(plus.force_a - minus.force_a) / (2 * h)
            Kfd[1, j, :, c] = -(plus.force_b - minus.force_b) / (2 * h)
    # the central difference errs by (h / L)^2 f''' / 6 (~1e-10 relative, h = 1 mm) and
    # by the solver's force error over h (tolerance 1e-12 of the nodal loads, ~1e-9 N,
    # over 2 mm: 1e-6 N/m against ~1e2 N/m): 1e-6 of the largest entry covers both
    # (measured 2.4e-9). The Gauss-Newton tangent alone misses by ~1e-2 here.
    scale = float(np.max(np.abs(K)))
    assert np.max(np.abs(K - Kfd)) <= 1e-6 * scale
    # a conservative line: K[i, j] = K[j, i]^T to round-off of the condensation
    for i in range(2):
        for j in range(2):
            np.testing.assert_allclose(K[i, j], K[j, i].T, rtol=0, atol=1e-10 * scale)


def test_without_bending_the_discrete_system_converges_to_the_catenary_at_order_two() -> None:
    """EI = 0: the discrete system's tensions, junction position and body stiffness
    approach the catenary system's as h^2 (lumped loads on straight elements): halving
    h divides the error by 4 (the next term, h^4, changes that ratio by ~(h/L)^2 < 1 %
    at 10 elements; 3.6..4.4 leaves room for the solvers' 1e-11 tolerance)."""
    exact = _numbers(_solve(hanging_system("catenary", 11)))
    errors = [
        float(np.max(np.abs(_numbers(_solve(hanging_system("discrete", n))) - exact)))
        for n in (11, 21, 41)
    ]
    assert 0.0 < errors[-1] < 1e-3  # 41 nodes: within 1e-3 of the tensions (1e4 N) etc.
    for coarse, fine in zip(errors, errors[1:], strict=False):
        assert 3.6 <= coarse / fine <= 4.4, errors


def test_with_bending_the_system_converges_and_bending_changes_it() -> None:
    """EI = 3e5 N m^2 on every line: successive refinements' differences shrink by 4
    (order two, as above); the converged answer differs from the cable's by far more
    than its mesh error (the bending stiffness is used, not dropped)."""
    ei = ", bending_stiffness: 3.0e5"
    runs = [_numbers(_solve(hanging_system("discrete", n, ei))) for n in (11, 21, 41, 81)]
    steps = [float(np.max(np.abs(b - a))) for a, b in zip(runs, runs[1:], strict=False)]
    for coarse, fine in zip(steps, steps[1:], strict=False):
        assert 3.6 <= coarse / fine <= 4.4, steps
    mesh_error = steps[-1] / 3.0  # Richardson: the error of the finest is step / (4 - 1)
    cable = _numbers(_solve(hanging_system("discrete", 81)))
    assert float(np.max(np.abs(runs[-1] - cable))) > 100.0 * mesh_error


def test_bending_in_a_catenary_system_is_refused_by_name() -> None:
    text = hanging_system("catenary", 11, ", bending_stiffness: 3.0e5")
    with pytest.raises(StudyError, match=r"lines\.leg1\.segments\.0\.bending_stiffness.*discrete"):
        expand_cases(parse_study_text(text, "hang.yaml"))
