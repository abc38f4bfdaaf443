"""An exported MoorDyn input file runs in MoorDyn and reads into MoorPy (optional extra
`peers`), and their static fairlead forces agree with our static solution.

MoorDyn finds its initial state by running the line to rest and stops when the
fairlead tensions change by less than ``threshIC`` (relative; the exported file sets
1e-3). Its lumped-mass chain carries the half-segment weights at the end nodes, and the
force on the coupled fairlead point is the whole end force, so its discretisation
error is of order (segment length / line length)^2 ~ (1/20)^2 / 12 ~ 2e-4 for the
segment counts below (measured: 3e-4): below ``threshIC``. We therefore require agreement
to ``threshIC`` in each component, relative to the end tension.
"""

from __future__ import annotations

import contextlib
import os
import re
import tempfile
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import xarray as xr

from cablestudy.analyses.static import solve_static
from cablestudy.cli import main
from cablestudy.interchange import InterchangeError, import_model, imported_yaml, parse_moordyn
from cablestudy.interchange.mapping import select_chain
from cablestudy.interchange.moordyn_scope import point_of
from cablestudy.study.grid import expand_cases
from cablestudy.study.loader import parse_study_text

ROOT = Path(__file__).resolve().parents[2]
PEERS = (
    "in the optional extra `peers` (pip install '.[peers]'); without it the exported file "
    "cannot be run"
)

STUDY = """
name: peer-check
environment: {fluid: water, depth: 300.0}
line:
  segments:
    - {length: 120.0, diameter: 0.08, mass_per_length: 40.0, axial_stiffness: 5.0e8}
    - {length: 100.0, diameter: 0.12, mass_per_length: 20.0, axial_stiffness: 2.0e8}
  attachments:
    - {s: 60.0, mass: 800.0, volume: 0.1}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -250.0]}
  b: {kind: fixed, position: [140.0, 0.0, -120.0]}
analysis:
  static: {method: catenary, nodes: 41, tolerance: 1.0e-12}
"""


@contextlib.contextmanager
def _quiet() -> Iterator[None]:
    saved = [os.dup(1), os.dup(2)]
    with open(os.devnull, "w") as null:
        os.dup2(null.fileno(), 1)
        os.dup2(null.fileno(), 2)
        try:
            yield
        finally:
            for fd, target in zip(saved, (1, 2), strict=True):
                os.dup2(fd, target)
                os.close(fd)


def test_exported_file_runs_in_moordyn_with_our_fairlead_force(tmp_path: Path) -> None:
    moordyn = pytest.importorskip("moordyn", reason=f"MoorDyn is {PEERS}")
    study = tmp_path / "study.yaml"
    study.write_text(STUDY)
    path = tmp_path / "line.dat"
    assert main(["export", "moordyn", str(study), "--out", str(path)]) == 0
    assert main(["run", str(study), "--out", str(tmp_path), "--no-progress"]) == 0
    with xr.open_dataset(tmp_path / "peer-check.nc") as ds:
        ours = ds.force_b.values.astype(float)
    text = path.read_text()
    thresh = float(re.search(r"^(\S+)\s+threshIC", text, re.M).group(1))
    row = re.search(r"^(\d+)\s+Coupled\s+(\S+)\s+(\S+)\s+(\S+)", text, re.M)
    pid, x0 = int(row.group(1)), np.array([float(row.group(k)) for k in (2, 3, 4)])
    np.testing.assert_array_equal(x0, [140.0, 0.0, -120.0])
    with _quiet():
        system = moordyn.Create(str(path))
        moordyn.Init(system, x0, np.zeros(3))
        theirs = np.array(moordyn.GetPointForce(moordyn.GetPoint(system, pid)))
        moordyn.Close(system)
    tension = np.linalg.norm(ours)
    assert np.abs(theirs - ours).max() <= thresh * tension, (theirs, ours)


def test_moorpy_reads_the_exported_file_to_the_same_equilibrium(tmp_path: Path) -> None:
    """MoorPy (a quasi-static catenary code) reads the exported MoorDyn file, solves the
    free points' equilibrium (tolerance 1e-7 m on their positions) and finds the same
    fairlead force as ours: its catenary is exact, so the two agree to the position
    tolerance times the line's stiffness EA / L ~ 2e6 N/m, i.e. about 1e-6 of the
    tension."""
    mp = pytest.importorskip("moorpy", reason=f"MoorPy is {PEERS}")
    study = tmp_path / "study.yaml"
    study.write_text(STUDY)
    path = tmp_path / "line.dat"
    assert main(["export", "moordyn", str(study), "--out", str(path)]) == 0
    assert main(["run", str(study), "--out", str(tmp_path), "--no-progress"]) == 0
    with xr.open_dataset(tmp_path / "peer-check.nc") as ds:
        ours = ds.force_b.values.astype(float)
    with _quiet():
        system = mp.System(file=str(path))
        system.initialize()
        system.solveEquilibrium(tol=1e-7)
    fairlead = system.pointList[-1]
    np.testing.assert_array_equal(fairlead.r, [140.0, 0.0, -120.0])
    theirs = np.asarray(fairlead.getForces(), dtype=float)
    np.testing.assert_allclose(theirs, ours, atol=1e-6 * np.linalg.norm(ours))


# ------------------------------------------------- the peers' own files, against MoorPy
PEER_DATA = Path(__file__).parents[1] / "data"
PEER_FILES = sorted(
    p
    for p in PEER_DATA.rglob("*")
    if p.suffix in (".txt", ".dat")
    and p.name != "current_profile.txt"
    and not p.name.startswith("LICENSE")
)


def _imported_statics(path: Path, line: int) -> tuple[Any, Any] | None:
    """(study, static result) of one line of a peer file imported alone, or None when it
    is refused or its statics do not settle (tests/unit/test_interchange_moordyn.py)."""

    try:
        imported = import_model(path.read_text(), path.name, lines=[line], folder=path.parent)
    except InterchangeError:
        return None
    _, cases = expand_cases(parse_study_text(imported_yaml(imported, path.name), "<i>"))
    result = solve_static(cases[0], None)
    return (cases[0].study, result) if result.success else None


def _moorpy_end_forces(
    mp: Any, path: Path, line: int, study: Any
) -> tuple[np.ndarray, np.ndarray] | None:
    """MoorPy's forces of the line on its ends A and B (6,), in the file's A-to-B order,
    and the ends' positions (6,),
    from MoorPy's own reading of the file with MoorDyn's environment (gravity, density,
    depth, which MoorPy's defaults differ from); None when MoorPy finds no solution."""

    from moorpy.Catenary import catenary  # an optional peer, imported where used

    env = study.environment
    with _quiet():
        system = mp.System(file=str(path))
        system.g, system.rho, system.depth = env.gravity, env.density, env.depth
        system.initialize()
        if any(e.kind == "force" for e in (study.ends.a, study.ends.b)):
            if not system.solveEquilibrium(tol=1e-9):
                return None
            # MoorPy may stop short of equilibrium (a weightless line): its free points'
            # net forces tell
            scale = max(float(np.abs(p.getForces()).max()) for p in system.pointList)
            for p in system.pointList:
                if p.type == 0 and np.abs(p.getForces()).max() > 1e-6 * scale:
                    return None
        ln = system.lineList[line - 1]
        mu = env.seabed.friction
        if mu > 0.0:
            # MoorPy's System zeroes the friction of a line anchored on the seabed; its
            # catenary takes it as CB, with end A on the seabed
            (seg,) = study.line.segments
            w = (seg.mass_per_length - env.density * seg.area) * env.gravity
            r_a, r_b = (np.asarray(r, dtype=float) for r in (ln.rA, ln.rB))
            if r_a[2] > r_b[2]:
                r_a, r_b = r_b, r_a
            dx = r_b - r_a
            h = float(np.hypot(dx[0], dx[1]))
            fah, fav, fbh, fbv, _ = catenary(
                h, dx[2], seg.length, seg.axial_stiffness, w, CB=mu, Tol=1e-12, MaxIter=200
            )
            u = dx[:2] / h
            f_low = np.array([fah * u[0], fah * u[1], fav])
            f_high = np.array([fbh * u[0], fbh * u[1], fbv])
            forces = np.hstack([f_low, f_high])
            if np.asarray(ln.rA)[2] > np.asarray(ln.rB)[2]:
                forces = np.hstack([f_high, f_low])
        else:
            ln.staticSolve(tol=1e-10)
            forces = np.hstack([ln.fA, ln.fB]).astype(float)
        ends = np.hstack([ln.rA, ln.rB]).astype(float)
    return (forces, ends) if np.all(np.isfinite(forces)) and np.all(np.isfinite(ends)) else None


def test_peer_files_lines_agree_with_moorpy() -> None:
    """Each line of the peer files that imports alone and settles (status 0) against
    MoorPy reading the same file (its own parser), in still water: MoorPy's statics have
    no current, so lines in a current are left out, and so are lines MoorPy finds no
    solution for (it raises, returns NaN, or its equilibrium of a free end fails).

    Tolerance, in each end-force component: both codes solve the elastic catenary to a
    relative position error of at most ``tol`` = max(our 1e-9, MoorPy's 1e-10), so the end
    forces agree to ``tol`` times the line's axial stiffness EA (a position error times
    the stiffness EA / L, over the length L) plus ``tol`` times the tension. A line with
    bending stiffness is solved by our discrete (lumped-mass) method, which places each
    element's weight at its nodes and the touchdown within an element: one element's
    weight in water, w L / NumSegs, is added (MoorPy ignores EI; these lines are slender
    enough that bending is below that bound). Measured: see the README of tests/data."""
    mp = pytest.importorskip("moorpy", reason=f"MoorPy is {PEERS}")
    agree, worst, left_out = 0, {"catenary": [0, 0.0], "discrete": [0, 0.0]}, []
    for path in PEER_FILES:
        rel = path.relative_to(PEER_DATA).as_posix()
        try:
            lines = sorted(parse_moordyn(path.read_text(), rel).lines)
        except InterchangeError:  # the one file MoorDyn refuses too (tests/unit)
            continue
        for line in lines:
            solved = _imported_statics(path, line)
            if solved is None:
                continue
            study, ours = solved
            if study.environment.has_current:
                left_out.append((rel, line, "current"))
                continue
            try:
                peer = _moorpy_end_forces(mp, path, line, study)
            except Exception as exc:  # MoorPy's LineError, CatenaryError, ...
                left_out.append((rel, line, f"MoorPy: {exc}"))
                continue
            if peer is None:
                left_out.append((rel, line, "MoorPy finds no solution"))
                continue
            theirs, r_ab = peer
            ours_f = np.hstack([ours.force_a, ours.force_b])
            ours_r = np.hstack([ours.position[0], ours.position[-1]])
            if np.abs(ours_r - r_ab).max() > np.abs(ours_r[[3, 4, 5, 0, 1, 2]] - r_ab).max():
                ours_f = ours_f[[3, 4, 5, 0, 1, 2]]  # imported from the file's B to its A
            vertical = np.all(ours_f[[0, 1, 3, 4]] == 0.0)
            if vertical and ours_f[2] * theirs[2] > 0.0 and ours_f[5] * theirs[5] < 0.0:
                # a line on one vertical, slack by its stretch: MoorPy takes it as a bar in
                # compression (its lower end pushed up by the slack's weight), a cable
                # folds below that end instead (tests/unit/test_statics_vertical.py)
                left_out.append((rel, line, "vertical: MoorPy's bar in compression"))
                continue
            segs = study.line.segments
            tol = 1e-9 * (max(s.axial_stiffness for s in segs) + np.abs(ours_f).max())
            if any(s.bending_stiffness > 0.0 for s in segs):
                rho, g = study.environment.density, study.environment.gravity
                n_elements = study.analysis.static.nodes - 1
                tol += max(abs(s.weight_in(rho, g)) for s in segs) * (
                    study.line.total_length / n_elements
                )
            err = float(np.abs(ours_f - theirs).max())
            assert err <= tol, (rel, line, ours_f, theirs, tol)
            agree += 1
            how = study.analysis.static.method
            worst[how][0] += 1
            worst[how][1] = max(worst[how][1], err / float(np.abs(ours_f).max()))
    print(f"agree with MoorPy: {agree} lines; by method [lines, largest difference / tension]:")
    print(worst)
    print("left out:", left_out)
    assert agree >= 30, left_out


def test_peer_files_chains_through_free_points_agree_with_moorpy() -> None:
    """The peer files whose lines form one chain through free points (a clump, a buoy, a
    junction), imported whole as one cablestudy line, against MoorPy's equilibrium of
    the same file: the forces on the chain's two end points. Tolerance as for one line,
    1e-9 (EA + T), plus MoorPy's equilibrium tolerance on the free points' positions
    (1e-10 m) times the stiffest line's EA / L. The chains whose statics our solvers do
    not settle (tests/unit SOLVER_GAPS) are left out."""
    mp = pytest.importorskip("moorpy", reason=f"MoorPy is {PEERS}")

    compared = []
    for path in PEER_FILES:
        rel = path.relative_to(PEER_DATA).as_posix()
        try:
            md = parse_moordyn(path.read_text(), rel)
            imported = import_model(path.read_text(), path.name, folder=path.parent)
        except InterchangeError:
            continue
        if len(md.lines) < 2 or "lines" in imported.data:  # systems: their own test
            continue
        _, cases = expand_cases(parse_study_text(imported_yaml(imported, path.name), "<i>"))
        ours = solve_static(cases[0], None)
        if not ours.success:
            continue
        study = cases[0].study
        chain, start = select_chain(md, None)
        last, reversed_ = chain[-1]
        end = last.attach_a if reversed_ else last.attach_b
        with _quiet():
            system = mp.System(file=str(path))
            env = study.environment
            system.g, system.rho, system.depth = env.gravity, env.density, env.depth
            system.initialize()
            assert system.solveEquilibrium(tol=1e-10)
            theirs = np.hstack(
                [system.pointList[point_of(md, k).id - 1].getForces() for k in (start, end)]
            )
        ours_f = np.hstack([ours.force_a, ours.force_b])
        segs = study.line.segments
        stiffness = max(md.line_types[ln.line_type].axial_stiffness for ln, _ in chain)
        shortest = min(ln.length for ln, _ in chain)
        tol = 1e-9 * (max(s.axial_stiffness for s in segs) + np.abs(ours_f).max())
        tol += 1e-10 * float(stiffness) / shortest
        err = float(np.abs(ours_f - theirs).max())
        assert err <= tol, (rel, ours_f, theirs, tol)
        compared.append((rel, err / float(np.abs(ours_f).max())))
    print("chains against MoorPy:", compared)
    assert len(compared) >= 3


def _surge_extremes(
    moordyn: Any, text: str, x0: np.ndarray, dtm: float, periods: int = 4
) -> tuple[float, float]:
    """MoorDyn's largest and smallest fairlead tension [N] over the last of ``periods``
    periods of the file ``text`` at time step ``dtm``, its coupled point at ``x0`` moved
    2 sin(2 pi 0.1 t) m in x after a ramp over the first period ((1 - cos(pi t / 10)) /
    2, as ours), handed the motion 128 times a period."""
    text = re.sub(r"^\S+(\s+dtM)", f"{dtm!r}\\1", text, flags=re.M)
    with tempfile.TemporaryDirectory() as tmp, _quiet():
        path = Path(tmp) / "line.dat"
        path.write_text(text)
        system = moordyn.Create(str(path))
        moordyn.Init(system, x0, np.zeros(3))
        w, step, t, out = 2.0 * np.pi * 0.1, 10.0 / 128, 0.0, []
        for _ in range(periods * 128):
            tn = t + step
            ramp, dramp = (
                (0.5 * (1.0 - np.cos(np.pi * tn / 10.0)), 0.05 * np.pi * np.sin(np.pi * tn / 10.0))
                if tn < 10.0
                else (1.0, 0.0)
            )
            x = x0 + [2.0 * ramp * np.sin(w * tn), 0.0, 0.0]
            v = [2.0 * (ramp * w * np.cos(w * tn) + dramp * np.sin(w * tn)), 0.0, 0.0]
            out.append(np.linalg.norm(moordyn.Step(system, x, v, t, step)))
            t = tn
        moordyn.Close(system)
    last = np.array(out[-128:])
    return float(last.max()), float(last.min())


def test_exported_seabed_friction_acts_and_its_time_step_is_stable(tmp_path: Path) -> None:
    """The chain of configs/chain-mooring-surge.yaml (310 m laid, friction 0.5) surged 2 m
    at 0.1 Hz: the exported file sets MoorDyn's friction to saturate at 2 cm/s on a laid
    node (FricDamp = w l / 0.02 m/s, from the file's own line type; MoorDyn's default of
    200 N s/m would saturate near 100 m/s, no friction), and MoorDyn at the exported dtM
    gives the extremes it gives at a quarter of it (a stable, converged step: 1e-4 of
    T_max; 4e-7 measured). Against ours at the same 40 elements and T/128: within 5e-3
    of T_max (measured 3.0e-3 and 1.1e-3; each code is within about 1e-3 of a converged
    reference here, benchmarks/wp_chain_moordyn.py, and the friction laws differ:
    halving the slip speed moves MoorDyn's maximum by 6e-4)."""
    moordyn = pytest.importorskip("moordyn", reason=f"MoorDyn is {PEERS}")
    text = (ROOT / "configs" / "chain-mooring-surge.yaml").read_text().split("sweep:")[0]
    study = tmp_path / "chain.yaml"
    study.write_text(text.replace("name: chain-mooring-surge", "name: chain"))
    path = tmp_path / "chain.dat"
    assert main(["export", "moordyn", str(study), "--out", str(path)]) == 0
    exported = path.read_text()
    row = re.search(r"^seg1\s+(\S+)\s+(\S+)", exported, re.M)
    d, mass = float(row.group(1)), float(row.group(2))
    weight = (mass - 1025.0 * np.pi * d**2 / 4.0) * 9.80665 * 800.0 / 40.0
    fric_damp = float(re.search(r"^(\S+)\s+FricDamp", exported, re.M).group(1))
    assert fric_damp == pytest.approx(weight / 0.02, rel=1e-9)
    assert re.search(r"^1\s+StatDynFricScale", exported, re.M)
    dtm = float(re.search(r"^(\S+)\s+dtM", exported, re.M).group(1))
    x0 = np.array([750.0, 0.0, -10.0])
    t_max, t_min = _surge_extremes(moordyn, exported, x0, dtm)
    fine = _surge_extremes(moordyn, exported, x0, dtm / 4.0)
    assert abs(t_max - fine[0]) <= 1e-4 * t_max and abs(t_min - fine[1]) <= 1e-4 * t_max
    assert main(["run", str(study), "--out", str(tmp_path), "--no-progress"]) == 0
    with xr.open_dataset(tmp_path / "chain.nc") as ds:
        ours = float(ds.tension_max), float(ds.tension_min)
    assert abs(t_max - ours[0]) <= 5e-3 * ours[0] and abs(t_min - ours[1]) <= 5e-3 * ours[0]


def test_exported_undamped_line_steps_without_growth(tmp_path: Path) -> None:
    """An undamped chain (tests/integration/test_step_check.py: 320 m, EA 5e8 N, 20 m
    nodes, no axial damping, landing and lifting off each period): MoorDyn's RK2 grows an
    undamped mode omega by (omega dt)^4 / 8 a step, which blew the file up at dtM 1e-3
    (maximum 984 kN against 131 kN; 312 kN at 5e-4). The export writes the damping
    ratio (omega dtM)^3 / 4 of its fastest axial mode omega = 2 c / l, warns, and MoorDyn
    at dtM gives the extremes it gives at a quarter of it within 3e-2 of T_max (measured
    1.5e-2 over eight periods: the undamped ringing after each landing converges slowly
    in the step at 128 handovers a period)."""
    moordyn = pytest.importorskip("moordyn", reason=f"MoorDyn is {PEERS}")
    from tests.integration.test_step_check import LEG

    study = tmp_path / "leg.yaml"
    study.write_text(LEG % "leg")
    path = tmp_path / "leg.dat"
    assert main(["export", "moordyn", str(study), "--out", str(path)]) == 0
    exported = path.read_text()
    dtm = float(re.search(r"^(\S+)\s+dtM", exported, re.M).group(1))
    c = np.sqrt(5.0e8 / 50.0)
    assert np.pi * 20.0 / (10.0 * c) / 2.5 < dtm <= np.pi * 20.0 / (10.0 * c)  # axial rule
    ba = float(re.search(r"^seg1\s+\S+\s+\S+\s+\S+\s+(\S+)", exported, re.M).group(1))
    assert ba == pytest.approx(-((2.0 * c / 20.0 * dtm) ** 3) / 4.0, rel=1e-12)
    x0 = np.array([10.0, 0.0, -10.0])
    t_max, t_min = _surge_extremes(moordyn, exported, x0, dtm, periods=8)
    fine = _surge_extremes(moordyn, exported, x0, dtm / 4.0, periods=8)
    assert abs(t_max - fine[0]) <= 3e-2 * t_max and abs(t_min - fine[1]) <= 3e-2 * t_max
