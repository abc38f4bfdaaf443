"""A whole mooring system against NREL/MoorPy: its ``tests/case8.dat`` (licence in
``tests/data/moorpy/LICENSE.txt``), three legs with bridles to a body, read by MoorPy's
own parser and built here point by point (tests/system_models.py).

Tolerances:
* end tensions: MoorPy solves the free junctions to ``tol`` 1e-8 m and its catenary to
  1e-10 relative; the end tensions then agree to ~1e-12 of the largest tension, and
  the issue's bound (1e-5 of the largest tension) leaves room for MoorPy's tolerances;
* body stiffness: within 1e-3 of its largest diagonal entry of MoorPy's analytic
  ``getCoupledStiffnessA`` (observed 1e-5) and of its finite difference
  ``getCoupledStiffness`` with small steps (dx 1 mm, dth 1e-4 rad; observed 5e-4).
  MoorPy's finite difference with its default steps (0.1 m, 0.1 rad) is off by 4.5e-3
  of the largest diagonal: a one-sided difference over 0.1 rad carries a first-order
  error (K' dth / 2) plus the junctions' solve tolerance divided by the step; ours is
  exact to the solves' round-off (tests/unit/test_statics_system.py shows its
  second-order remainder), so ours is the more accurate.
"""

from __future__ import annotations

from pathlib import Path

import moorpy
import numpy as np

from cablestudy.statics import STATIC_SOLVERS
from cablestudy.statics.system import solve_system
from tests.system_models import CASE8_LINES, CASE8_POINTS, RHO, G, system_of

CASE8 = Path(__file__).parents[1] / "data" / "moorpy" / "tests" / "case8.dat"


def _moorpy() -> moorpy.System:
    ms = moorpy.System(file=str(CASE8))
    ms.initialize()
    ms.solveEquilibrium(tol=1e-8)
    assert ms.g == G and ms.rho == RHO and ms.depth == 100.0
    return ms


def test_case8_tensions_and_body_stiffness_match_moorpy() -> None:
    ours = solve_system(system_of(CASE8_POINTS, CASE8_LINES, [0.0] * 6), STATIC_SOLVERS["catenary"])
    assert ours.status == 0, ours.message
    ms = _moorpy()
    theirs = np.array([[ln.TA, ln.TB] for ln in ms.lineList])
    mine = np.array([[np.linalg.norm(r.force_a), np.linalg.norm(r.force_b)] for r in ours.lines])
    largest = float(np.max(theirs))
    assert np.max(np.abs(mine - theirs)) <= 1e-5 * largest
    junctions = np.array([p.r for p in ms.pointList if p.type == 0])
    np.testing.assert_allclose(ours.point_position[[3, 7, 11]], junctions, rtol=0, atol=1e-6)
    np.testing.assert_allclose(
        ours.body_force[0], ms.bodyList[0].getForces(lines_only=True), rtol=0, atol=1e-5 * largest
    )
    K = ours.body_stiffness[0]
    scale = float(np.max(np.diag(K)))
    analytic = ms.getCoupledStiffnessA(lines_only=True)
    assert np.max(np.abs(K - analytic)) <= 1e-3 * scale
    difference = ms.getCoupledStiffness(dx=1e-3, dth=1e-4, lines_only=True)
    assert np.max(np.abs(K - difference)) <= 1e-3 * scale
