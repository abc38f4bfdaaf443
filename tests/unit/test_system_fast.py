"""The compiled system Newton (:mod:`cablestudy.statics.system_fast`) against the general
path (:func:`cablestudy.statics.system.solve_system` with ``compiled=False``).

Both solve the same equations: the free points' net force to the system tolerance
(1e-9 or 1e-12 relative to the largest tension) and then one more Newton step, which
squares the relative error; each line to its own tolerance, polished the same way. So
the two agree to round-off times the conditioning (measured: 1e-13 at worst, case8's
bridles), and 1e-9 relative, the issue's bar for equal answers, still catches any wrong
term: a missing or wrong stiffness block changes the body stiffness at O(1), a wrong
line branch (on the seabed or hanging free) the tensions at O(1).

Scales: tensions against the largest end tension; positions against the longest line;
the body force's moment against the largest tension times the largest lever arm; each
stiffness entry K_ij against sqrt(|K_ii K_jj|), the scale of its own units.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from cablestudy.analyses.system import system_model
from cablestudy.interchange import import_model, imported_yaml
from cablestudy.statics import STATIC_SOLVERS
from cablestudy.statics.system import solve_system
from cablestudy.statics.system_fast import solve_fast
from cablestudy.study.grid import expand_cases
from cablestudy.study.loader import parse_study_text
from tests.system_models import CASE8_LINES, CASE8_POINTS, system_of

DATA = Path(__file__).parents[1] / "data"
#: every peer file that imports as a system (tests/validation/test_system_moordyn_peer.py)
SYSTEM_FILES = [
    "moordyn/example/MHK_RM1_Floating/MHK_RM1_Floating_MoorDyn.dat",
    "moordyn/example/body.txt",
    "moordyn/example/lines.txt",
    "moordyn/tests/Mooring/lines.txt",
    "moordyn/tests/Mooring/local_euler/duplicated.txt",
    "moorpy/examples/sample.txt",
    "moorpy/tests/case8.dat",
    "moorpy/tests/case9.dat",
]
RTOL = 1e-9


def _imported(rel: str):  # noqa: ANN202
    path = DATA / rel
    imported = import_model(path.read_text(), rel, folder=path.parent)
    _, cases = expand_cases(parse_study_text(imported_yaml(imported, rel), "<imported>"))
    return system_model(cases[0].study)


def _compare(system) -> None:  # noqa: ANN001
    ref = solve_system(system, STATIC_SOLVERS["catenary"], compiled=False)
    assert ref.status == 0, ref.message
    got, why = solve_fast(system)
    assert why == "" and got is not None  # the compiled path took it
    ten_ref = np.array([[np.linalg.norm(r.force_a), np.linalg.norm(r.force_b)] for r in ref.lines])
    ten = np.array([[np.linalg.norm(r.force_a), np.linalg.norm(r.force_b)] for r in got.lines])
    big = float(ten_ref.max())
    assert np.max(np.abs(ten - ten_ref)) <= RTOL * big
    for a, b in zip(got.lines, ref.lines, strict=True):
        np.testing.assert_allclose(a.force_a, b.force_a, rtol=0, atol=RTOL * big)
        np.testing.assert_allclose(a.force_b, b.force_b, rtol=0, atol=RTOL * big)
        np.testing.assert_allclose(a.tension, b.tension, rtol=0, atol=RTOL * big)
        np.testing.assert_allclose(a.laid_length, b.laid_length, rtol=0, atol=RTOL * a.s[-1])
    reach = max(float(ln.problem.line.total_length) for ln in system.lines)
    for a, b in zip(got.lines, ref.lines, strict=True):
        np.testing.assert_allclose(a.position, b.position, rtol=0, atol=RTOL * reach)
    np.testing.assert_allclose(got.point_position, ref.point_position, rtol=0, atol=RTOL * reach)
    if not system.body_names:
        return
    arm = max(reach, float(np.max(np.abs(system.point_position))))
    np.testing.assert_allclose(got.body_force[:, :3], ref.body_force[:, :3], atol=RTOL * big)
    np.testing.assert_allclose(got.body_force[:, 3:], ref.body_force[:, 3:], atol=RTOL * big * arm)
    for K, K_ref in zip(got.body_stiffness, ref.body_stiffness, strict=True):
        d = np.abs(np.diag(K_ref))
        scale = np.sqrt(np.outer(d, d))
        assert np.all(np.abs(K - K_ref) <= RTOL * scale + 1e-300), np.max(np.abs(K - K_ref) / scale)


def test_case8_compiled_equals_general() -> None:
    """MoorPy's case8 (three free junctions, bridles to a body, legs lifting off the
    seabed), at rest and offset 15 m in surge and 0.1 rad in yaw."""
    _compare(system_of(CASE8_POINTS, CASE8_LINES, [0.0] * 6))
    _compare(system_of(CASE8_POINTS, CASE8_LINES, [15.0, -4.0, 1.0, 0.02, -0.03, 0.1]))


@pytest.mark.parametrize("rel", SYSTEM_FILES)
def test_peer_system_files_compiled_equals_general(rel: str) -> None:
    """Every peer system file under tests/data (lines on the seabed to bodies, lines
    lifting off, free points, case9's line hanging free between two anchors' bodies)."""
    _compare(_imported(rel))


def test_what_the_kernel_cannot_take_goes_to_the_general_path_with_its_reason() -> None:
    """A junction below the seabed: the compiled path refuses it (a line with a moving end
    on the seabed), says why, and solve_system gives the general path's answer with that
    reason in ``fallback``."""
    points = [list(p) for p in CASE8_POINTS]
    points[3][2] = [34.64, -20.0, -100.0]  # junction 4 starts on the seabed
    system = system_of([tuple(p) for p in points], CASE8_LINES, [0.0] * 6)
    got, why = solve_fast(system)
    assert got is None and "seabed" in why
    res = solve_system(system, STATIC_SOLVERS["catenary"])
    ref = solve_system(system, STATIC_SOLVERS["catenary"], compiled=False)
    assert res.fallback == why
    assert res.status == ref.status and res.message == ref.message


@pytest.mark.parametrize("rel", SYSTEM_FILES)
def test_final_lines_are_the_batch_solvers_for_the_same_ends(rel: str) -> None:
    """The compiled path's lines at its solution are :func:`solve_batch`'s for the same
    end positions, bit for bit (what a sweep's grid and a case share): an anchored line
    the Newton left hanging free (case8's taut legs, lifted off their anchors) is solved
    hanging at once, the numbers the contact solve hands on after lifting it off; a line
    laid from its anchor (lines.txt's chains) goes through the contact solve."""
    from dataclasses import replace

    from cablestudy.statics import EndCondition
    from cablestudy.statics.batch import solve_batch

    system = _imported(rel)
    got, why = solve_fast(system)
    assert why == "" and got is not None
    pos = got.point_position

    def fixed(i: int) -> EndCondition:
        return EndCondition(kind="fixed", position=pos[i].copy())

    problems = [replace(ln.problem, end_a=fixed(ln.a), end_b=fixed(ln.b)) for ln in system.lines]
    for mine, ref in zip(got.lines, solve_batch(problems), strict=True):
        assert ref.status == 0, ref.message
        for name in ("position", "tension", "force_a", "force_b", "laid_length"):
            assert np.array_equal(getattr(mine, name), getattr(ref, name)), name
    if rel.endswith("case8.dat"):  # the legs: anchored on the seabed, lifted off
        depth = system.lines[0].problem.medium.depth
        on_bed = [k for k, ln in enumerate(system.lines) if pos[ln.a][2] <= -depth]
        assert len(on_bed) == 3 and all(got.lines[k].laid_length == 0.0 for k in on_bed)
