"""The compiled seabed-contact kernel (cablestudy.statics._fast_contact) against the
general numpy path (``SemiAnalyticSolver.solve(compiled=False)``: solve_contact with
seabed.laid_part) and against MoorPy's ``catenary`` with seabed friction (CB), and a
swept mooring study written as a user writes it (no ``method`` key) taking the array
path with no case left to the general solver.

Tolerances. Both solvers stop when the end-B residual max|r_B - r_B target| / L is below
the study tolerance ``tol`` (1e-9 here) and then take one more Newton step (quadratic
convergence: the residual drops to round-off). Each solution therefore meets the end
condition to tol * L, and two solutions of the same equations differ in position by at
most 2 tol L; the tensions differ by at most the line's end stiffness times that, and
the end stiffness is below EA / L_s (the axial stiffness of the suspended length L_s,
the geometric part being softer), so |dT| <= 2 tol L EA / L_s. The laid length differs
by at most the position bound over the laid part's stretch factor (>= 1): 2 tol L.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from cablestudy import cli
from cablestudy.analyses.static_grid import evaluate_grid_chunk
from cablestudy.statics import STATIC_SOLVERS
from cablestudy.statics.batch import solve_batch
from cablestudy.statics.batch_kernels import contact_eligible, contact_end, solve_compiled
from cablestudy.statics.semi_analytic import SemiAnalyticSolver
from cablestudy.study import parse_study_text
from cablestudy.study.grid import CaseGrid
from cablestudy.study.loader import validate_data
from cablestudy.study.problem import static_problem

TOL = 1e-9

#: a studless chain (76 mm, 126 kg/m, EA 5e8 N) in 100 m of water, 300 m long
CHAIN = """\
name: chain
environment:
  fluid: water
  depth: 100.0
  seabed: {{slope_deg: {slope}, slope_heading_deg: {heading}, friction: {mu}}}
line:
  segments:
{segments}
{attachments}
ends:
  a: {{kind: fixed, position: [0.0, 0.0, {za}]}}
  b: {{kind: fixed, position: [{xb}, {yb}, -10.0]}}
analysis:
  static: {{nodes: 41, tolerance: {tol}}}
"""
ONE = "    - {length: 300.0, diameter: 0.076, mass_per_length: 126.0, axial_stiffness: 5.0e8}"
#: chain - wire - chain with a clump weight on the bottom chain and a buoy on the wire
THREE = """\
    - {length: 120.0, diameter: 0.076, mass_per_length: 126.0, axial_stiffness: 5.0e8}
    - {length: 150.0, diameter: 0.064, mass_per_length: 20.0, axial_stiffness: 3.0e8}
    - {length: 40.0, diameter: 0.076, mass_per_length: 126.0, axial_stiffness: 5.0e8}"""
ATTACH = """\
  attachments:
    - {s: 60.0, force: [0.0, 0.0, -20000.0]}
    - {s: 200.0, force: [0.0, 0.0, 15000.0]}"""


def _problem(
    *, slope: float, heading: float, mu: float, multi: bool, xb: float, yb: float, at_b=False
):
    """The chain study as a static problem, anchored at A on the seabed (``at_b``: the
    ends swapped, anchored at B)."""
    za = -100.0
    text = CHAIN.format(
        slope=slope,
        heading=heading,
        mu=mu,
        segments=THREE if multi else ONE,
        attachments=ATTACH if multi else "",
        za=za,
        xb=xb,
        yb=yb,
        tol=TOL,
    )
    if at_b:
        a = f"[0.0, 0.0, {za}]"
        b = f"[{xb}, {yb}, -10.0]"
        text = text.replace(a, "@A").replace(b, a).replace("@A", b)
    src = parse_study_text(text, "chain.yaml")
    return static_problem(validate_data(src.data, src))


CASES = [
    pytest.param(
        slope, heading, mu, multi, xb, yb, id=f"{name}-mu{mu}-{'3seg' if multi else '1seg'}"
    )
    for name, slope, heading, xb, yb in (
        ("flat", 0.0, 0.0, 250.0, 0.0),
        ("up-slope", 3.0, 0.0, 250.0, 0.0),
        ("down-slope", 4.0, 180.0, 245.0, 0.0),
        ("oblique-slope", 3.0, 30.0, 230.0, 60.0),
    )
    for mu in (0.0, 0.5)
    for multi in (False, True)
]


def _slides(slope: float, heading: float, mu: float) -> bool:
    """A frictionless line laid on a slope that does not fall along the laid direction
    (every laid line here runs within 15 degrees of +x, so a slope heading other than 0
    or 180 degrees): the slope's cross component of the laid weight, mu = 0, has nothing
    to hold it. The kernel lays the line straight all the same, so its answer balances
    only with a sideways seabed reaction that a frictionless seabed cannot give:
    statics/verify.py refuses it and hands it on; the general solver refuses the state
    by name (status 4: no straight laid line, friction cannot hold it)."""
    return mu == 0.0 and slope > 0.0 and heading % 180.0 != 0.0


def _assert_refused_by_both_paths(
    prob,
    status: int = 4,
    words: str = "sliding sideways",  # noqa: ANN001
) -> None:
    assert solve_compiled(prob) is None  # the kernel's answer is not verified: handed on
    res = STATIC_SOLVERS["catenary"].solve(prob)
    assert res.status == status and words in res.message, res.message


def _reach(xb: float, multi: bool) -> float:
    # the three-piece line is heavier at its anchor end and carries a buoy: it needs
    # more offset to hold its touchdown point off the anchor's side (at 250 m both the
    # kernel and the numpy path fail the same line search)
    return xb + 20.0 if multi else xb


REVERSED = [
    pytest.param(*p.values, True, id=f"{p.id}-anchored-at-b")
    for p in CASES
    if p.id in ("flat-mu0.5-1seg", "oblique-slope-mu0.5-1seg")
]


def test_a_buoy_on_the_laid_part_is_refused_on_both_paths() -> None:
    """The three-piece line anchored at B: its laid part (about 120 m from B) holds the
    15 kN buoy at s = 200 m, which would lift some 90 m of the 164 N/m wire off the
    seabed. The laid-part model keeps the line straight on the seabed, so the whole-line
    balance needs the seabed to pull the line down there: the kernel hands it on, and the
    general solver refuses it by name (status 4; it was status 11, not verified), the
    buoy's s counted from A although the line is solved from B."""
    prob = _problem(
        slope=3.0, heading=30.0, mu=0.5, multi=True, xb=_reach(230.0, True), yb=60.0, at_b=True
    )
    assert contact_end(prob) == "b"
    _assert_refused_by_both_paths(prob, 4, "a buoy at s = 200 m lifts the line off the seabed")


@pytest.mark.parametrize(
    ("slope", "heading", "mu", "multi", "xb", "yb", "at_b"),
    [pytest.param(*p.values, False, id=p.id) for p in CASES] + REVERSED,
)
def test_kernel_agrees_with_the_numpy_contact_solver(
    slope: float, heading: float, mu: float, multi: bool, xb: float, yb: float, at_b: bool
) -> None:
    prob = _problem(
        slope=slope, heading=heading, mu=mu, multi=multi, xb=_reach(xb, multi), yb=yb, at_b=at_b
    )
    assert contact_end(prob) == ("b" if at_b else "a")
    if _slides(slope, heading, mu):
        _assert_refused_by_both_paths(prob)
        return
    why: dict[int, str] = {}
    fast = solve_compiled(prob, why=why)
    ref = SemiAnalyticSolver().solve(prob, compiled=False)
    if multi and (slope, heading, mu) == (3.0, 30.0, 0.5) and not at_b:
        # the kernel's contact Newton settles this line with its touchdown point at
        # s = 209 m, past the 15 kN buoy at s = 200 m: the laid part would hold the buoy
        # down, which the seabed cannot. It is handed on (contact_status.LIFTING_LOAD_LAID)
        # and the general solver, which keeps the touchdown point short of a load lifting
        # the line (statics/contact_pin.first_lift), answers with the buoy hanging
        assert fast is None, why
        assert ref.status == 0, ref.message
        assert 0.0 < ref.laid_length < 200.0
        return
    assert fast is not None and fast.status == 0  # the kernel settled it
    assert ref.status == 0, ref.message
    assert 0.0 < ref.laid_length < prob.line.total_length  # a laid part and a suspended one
    L = prob.line.total_length
    EA = float(prob.line.axial_stiffness.max())
    suspended = L - ref.laid_length
    dpos = 2.0 * TOL * L
    dT = 2.0 * TOL * L * EA / suspended
    np.testing.assert_allclose(fast.position, ref.position, rtol=0.0, atol=dpos)
    # the numpy path writes 1e-150 N on a slack laid part where the kernel writes 0
    np.testing.assert_allclose(fast.tension, ref.tension, rtol=0.0, atol=dT)
    np.testing.assert_allclose(fast.force_a, ref.force_a, rtol=0.0, atol=dT)
    np.testing.assert_allclose(fast.force_b, ref.force_b, rtol=0.0, atol=dT)
    assert abs(fast.laid_length - ref.laid_length) <= dpos
    assert np.all(fast.tension >= 0.0)


def test_friction_lays_a_slack_part_with_tension_exactly_zero() -> None:
    # flat seabed, mu = 0.5: the tension falls at mu w from the touchdown point and
    # reaches zero before the anchor (H / (mu w) < laid length); there it is exactly 0
    prob = _problem(slope=0.0, heading=0.0, mu=0.5, multi=False, xb=250.0, yb=0.0)
    res = solve_compiled(prob)
    assert res is not None and res.status == 0
    w = float(prob.line.weight[0])
    H = -float(res.force_b[0])  # horizontal tension, constant along the suspended part
    slack = res.laid_length - H / (0.5 * w)
    assert slack > 10.0
    on_slack = res.s < slack - 1e-9 * prob.line.total_length
    assert on_slack.sum() >= 5
    assert np.all(res.tension[on_slack] == 0.0)
    assert np.all(res.force_a == 0.0)
    # where tensioned, the laid tension rises at mu w towards the touchdown point and
    # meets the suspended part's tension H there (Coulomb friction fully mobilised; the
    # closed form of laid_part): equal up to the round-off of differences of lengths of
    # a few hundred metres, 1e-10 of H
    laid = (res.s > slack) & (res.s < res.laid_length)
    expect = 0.5 * w * (res.s[laid] - slack)
    np.testing.assert_allclose(res.tension[laid], expect, rtol=0.0, atol=1e-10 * H)


def test_slack_goes_to_the_general_solver_and_a_lifted_line_hangs_free() -> None:
    # B closer to the anchor than L - depth: slack on the seabed (no determined shape),
    # for the general solver to report
    prob = _problem(slope=0.0, heading=0.0, mu=0.5, multi=False, xb=150.0, yb=0.0)
    assert contact_eligible(prob) and solve_compiled(prob) is None
    ref = SemiAnalyticSolver().solve(prob)
    assert ref.status != 0 and "slack" in ref.message
    # B so far that the whole chain lifts off (flat and sloped): the touchdown point is
    # driven to the anchor and the free-hanging kernel takes the line, as the general
    # solver's suspended path does (bounds as in the module docstring with L_s = L)
    for slope in (0.0, 3.0):
        prob = _problem(slope=slope, heading=0.0, mu=0.5, multi=False, xb=290.0, yb=0.0)
        fast = solve_compiled(prob)
        ref = SemiAnalyticSolver().solve(prob, compiled=False)
        assert fast is not None and ref.status == 0
        assert fast.laid_length == 0.0 == ref.laid_length
        dT = 2.0 * TOL * 300.0 * 5e8 / 300.0
        np.testing.assert_allclose(fast.position, ref.position, rtol=0.0, atol=2 * TOL * 300)
        np.testing.assert_allclose(fast.tension, ref.tension, rtol=0.0, atol=dT)
    # lifted off with a buoy on the line (a load away from the seabed): whether the free
    # line dips into the seabed is not certain from the anchor, so the general solver
    # decides, counted
    prob = _problem(slope=0.0, heading=0.0, mu=0.5, multi=True, xb=295.0, yb=0.0)
    assert solve_compiled(prob) is None
    general: list[int] = []
    (res,) = solve_batch([prob], general=general)
    assert general == [0] and res.status == 0 and res.laid_length == 0.0


@pytest.mark.parametrize("mu", [0.0, 0.5, 1.0])
def test_fairlead_tension_agrees_with_moorpy_catenary(mu: float) -> None:
    # MoorPy (NREL, installed as a peer) solves the same elastic catenary with a
    # frictional seabed (CB = mu) for an anchor on the seabed at the origin: its
    # fairlead tension agrees to 1e-6 (both converged far below that: our tol 1e-9,
    # MoorPy's Tol 1e-10 on its own relative residual)
    from moorpy.Catenary import catenary

    for xb in (240.0, 250.0, 265.0):
        prob = _problem(slope=0.0, heading=0.0, mu=mu, multi=False, xb=xb, yb=0.0)
        res = solve_compiled(prob)
        assert res is not None and res.status == 0
        w = float(prob.line.weight[0])
        EA = float(prob.line.axial_stiffness[0])
        _, _, fbh, fbv, info = catenary(xb, 90.0, 300.0, EA, w, CB=mu, Tol=1e-10, MaxIter=200)
        ours = float(np.linalg.norm(res.force_b))
        theirs = math.hypot(fbh, fbv)
        assert abs(ours - theirs) <= 1e-6 * theirs, (xb, ours, theirs)
        assert abs(res.laid_length - info["LBot"]) <= 1e-6 * 300.0


SWEEP = """\
name: chain-sweep
environment: {fluid: water, depth: 100.0, seabed: {friction: 0.5}}
line:
  segments:
    - {length: 300.0, diameter: 0.076, mass_per_length: 126.0, axial_stiffness: 5.0e8}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -100.0]}
  b: {kind: fixed, position: [250.0, 0.0, -10.0]}
analysis:
  static: {nodes: 20}
sweep:
  ends.b.position.0: {start: 225.0, stop: 295.0, num: 15, name: offset}
  line.segments.0.axial_stiffness: [1.0e8, 5.0e8, 2.0e9]
"""


def test_a_seabed_sweep_without_method_key_runs_on_the_array_kernel(tmp_path) -> None:
    path = tmp_path / "chain-sweep.yaml"
    path.write_text(SWEEP)
    _, _, grid = cli._load(str(path))
    assert isinstance(grid, CaseGrid)
    chunk = evaluate_grid_chunk(grid, 0, grid.shape[0])
    assert np.all(chunk.fallback_reason == "")  # every case settled by the contact kernel
    assert np.all(chunk.status == 0)
    laid = chunk.data["laid_length"]
    assert np.any(laid > 0.0) and np.any(laid == 0.0)  # on the seabed and lifted off


@pytest.mark.parametrize("slope", [0.0, 3.0])
@pytest.mark.parametrize("mu", [0.0, 0.5])
@pytest.mark.parametrize(
    "end_b",
    [
        "{kind: mooring, force: [47000.0, 5000.0], z: -10.0}",
        "{kind: force, force: [47000.0, 0.0, 150000.0]}",
    ],
    ids=["mooring", "towed"],
)
@pytest.mark.parametrize("multi", [False, True], ids=["1seg", "3seg"])
def test_a_known_force_at_b_agrees_with_the_numpy_contact_solver(
    slope: float, mu: float, end_b: str, multi: bool
) -> None:
    # the contact Newton with the end-force residuals of solve_contact (the tension at B
    # against the known force, scaled by the line's weight or that force): the same
    # bounds as for a fixed B, the end condition now met to tol * Fscale in force
    text = CHAIN.format(
        slope=slope,
        heading=30.0,
        mu=mu,
        segments=THREE if multi else ONE,
        attachments=ATTACH if multi else "",
        za=-100.0,
        xb=250.0,
        yb=0.0,
        tol=TOL,
    ).replace("{kind: fixed, position: [250.0, 0.0, -10.0]}", end_b)
    src = parse_study_text(text, "chain.yaml")
    prob = static_problem(validate_data(src.data, src))
    assert contact_end(prob) == "a"
    ref = SemiAnalyticSolver().solve(prob, compiled=False)
    fast = solve_compiled(prob)
    if _slides(slope, 30.0, mu):  # also the towed three-piece line pinned at its clump
        _assert_refused_by_both_paths(prob)
        return
    if "force," in end_b and multi and slope > 0.0:
        # the towed three-piece line on the slope: its touchdown point rests at the
        # 20 kN clump (s = 60 m), the seabed carrying part of its weight: the general
        # solver's pinned contact state (statics/contact_pin.py) solves it (before it,
        # its line search failed there as the TDP crossed the clump); the kernel has no
        # such state and leaves it to the general solver
        assert ref.status == 0, ref.message
        assert abs(ref.laid_length - 60.0) <= 1e-9
        assert fast is None
        return
    assert ref.status == 0, ref.message
    assert fast is not None and 0.0 < ref.laid_length < 310.0
    L = prob.line.total_length
    suspended = L - ref.laid_length
    dT = 2.0 * TOL * L * 5e8 / suspended
    np.testing.assert_allclose(fast.position, ref.position, rtol=0.0, atol=2.0 * TOL * L)
    np.testing.assert_allclose(fast.tension, ref.tension, rtol=0.0, atol=dT)
    np.testing.assert_allclose(fast.force_b, ref.force_b, rtol=0.0, atol=dT)
    assert abs(fast.laid_length - ref.laid_length) <= 2.0 * TOL * L
