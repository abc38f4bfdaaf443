"""MoorDyn references for mooring systems driven by a body's motion (issue 24).

Writes ``tests/data/moordyn_system_refs/<case>.json``: each line's maximum and minimum
end tension (end A and end B as the file defines each line) over a steady window, with
MoorDyn's version, the settings, the refinement table and MoorDyn's wall time at each
level. Not part of ``make test`` (minutes of MoorDyn); run by hand:

    PYTHONPATH=$PWD .venv/bin/python benchmarks/make_moordyn_system_refs.py [CASE ...]

The cases (the issue's validation list):

- ``case8_surge``, ``case8_heave``: MoorPy's ``tests/case8.dat`` (a spar; three
  polyester legs, each splitting at a free junction into two bridles to the coupled body
  ``Body1`` at the origin), the body moved in surge 2 m and in heave 1 m at 0.1 Hz;
- ``lines_surge``, ``lines_pitch``: MoorDyn's ``tests/Mooring/lines.txt`` (OC3-Hywind:
  three 902.2 m chains, 77.7 kg/m, from anchors on the seabed at 320 m depth and 853.9 m
  radius to three coupled fairleads at 70 m draft and 5.2 m radius), the fairleads moved
  as one rigid body about the platform's reference point (0, 0, 0) (still water line on
  the spar's axis): surge 5 m at 0.05 Hz (a spar's surge in a 20 s swell), pitch 3 deg
  at 0.05 Hz (the fairleads 70 m below the reference move 3.7 m horizontally and 0.27 m
  vertically; the rotation is exact, not small-angle); and pitch 3 deg at 0.1 Hz
  (``lines_pitch_10s``), where leg 1's tension at its anchor falls to 110 kN as the
  chain lands on the seabed there: its minima converge slowly (they move by 4e-3 of
  the maximum with each doubling of the segments from 40 to 160, 2e-3 to 320), so
  this case refines once more (k = 16). Not surge 5 m at 0.1 Hz: the
  fairleads' 3.1 m/s then slacken leg 1 at its anchor (minimum tension -0.2 kN, MoorDyn
  at the file's mesh): snap loads, a test of the slack model rather than of the system.

How MoorDyn is driven:

- the file as it is, except: its initial condition from the dynamic relaxation settled
  (``ICgenDynamic 1``, ``threshIC 1e-6``; tests/validation/test_system_moordyn_ic.py
  says why the file's own settings leave it 25-81 % off on case8), no ``fileIC`` (a
  state file lines.txt names and that is not part of the input), no log file; and at
  refinement level k the segments of every line multiplied by k (NumSegs column) and
  ``dtM`` divided by k (the explicit step's stability limit scales with the segment
  length), ``dtM`` never above the file's;
- the body degree of freedom q(t) = A r(t) sin(2 pi f t), r = (1 - cos(pi t / t_r)) / 2
  over ``t_r`` = 2 periods, then 1 (smooth ramp: continuous velocity); a coupled body
  gets q as its six coordinates (position, Euler angles), coupled points get the exact
  rigid-body position of each point (translation + rotation matrix about the reference
  point). MoorDyn is handed the motion every ``T / SAMPLES`` with the secant velocity,
  so that its coupled positions follow the piecewise-linear interpolant of the exact
  motion (position error <= A (2 pi / SAMPLES)^2 / 8 = 2.5e-6 A at SAMPLES = 2000);
- tensions read after each hand-over: MoorDyn's node tensions (``GetLineNodeTen``,
  axial stiffness + internal damping). Node 0 carries segment 0's tension, node N the
  last segment's, inner nodes the mean of their two segments (checked on case8's
  equilibrium: the recursion seg_i = 2 node_i - seg_{i-1} from node 0 ends on node N
  to 1.7e-10 N). A segment's tension is that at its midpoint, half a segment from the
  end; the end tension is extrapolated linearly from the two end segments,
  T_end = 1.5 T_seg0 - 0.5 T_seg1 (second order in the segment length, like the
  lumped-mass model itself), and that is the reference. MoorDyn's raw end-node
  tensions (first order: short by about w L / (2 N) at a hanging end) are kept beside
  it in the table;
- steady window: the last of ``PERIODS`` periods; the change between the last two
  periods' extremes is recorded for every output (``transient``) and must be below
  ``TRANSIENT_BAR`` of the line's largest tension;
- convergence: levels k = 1, 2, 4, 8 (and 1/2 for the timing curve); converged when the
  change of every extreme from the previous level is below ``CONVERGED`` (0.2 %) of the
  maximum tension at the same line end (for a maximum: of itself; a minimum is scaled
  by its end's maximum, as a minimum near slack has no relative error to speak of); the
  reference is the finest level. A separate run at the finest level halves
  ``dtM`` and the hand-over interval (the time-step check).
- timing: CPU time (``time.process_time``: MoorDyn runs on one thread, and the machine
  is shared, so wall time measures the neighbours) of MoorDyn's ``Step`` calls per
  simulated second (the tension reads excluded), and of its initial condition, at each
  level, wall times beside; the error of each level is max over lines, ends and
  extremes of |T - T_ref| / T_max,ref at that end, for the extrapolated and the raw end
  tensions; MoorDyn's time to 1 % is that of the cheapest level within 1 %.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import re
import sys
import tempfile
import time
from collections.abc import Iterator
from dataclasses import dataclass
from importlib.metadata import version
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "tests" / "data"
OUT = DATA / "moordyn_system_refs"
PERIODS = 8  # simulated periods; the ramp takes the first two
RAMP_PERIODS = 2.0
SAMPLES = 2000  # hand-overs of the motion per period
CONVERGED = 2e-3  # largest change of an extreme between levels, of that extreme
TRANSIENT_BAR = 1e-3  # largest change between the last two periods, of the line's T_max
LEVELS = (0.5, 1, 2, 4, 8)
DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")


@dataclass(frozen=True)
class Case:
    file: str  # under tests/data
    dof: str
    amplitude: float  # [m] or [rad]
    frequency: float  # [Hz]
    reference_point: tuple[float, float, float] = (0.0, 0.0, 0.0)
    levels: tuple[float, ...] = LEVELS


CASES = {
    "case8_surge": Case("moorpy/tests/case8.dat", "surge", 2.0, 0.1),
    "case8_heave": Case("moorpy/tests/case8.dat", "heave", 1.0, 0.1),
    "lines_surge": Case("moordyn/tests/Mooring/lines.txt", "surge", 5.0, 0.05),
    "lines_pitch": Case("moordyn/tests/Mooring/lines.txt", "pitch", float(np.radians(3.0)), 0.05),
    # leg 1's anchor-end minimum (107 kN, the chain landing on the seabed at the
    # anchor) converges slowly: changes 4.9e-3, 4.2e-3, 4.0e-3, 2.0e-3 of its maximum
    # from 20 to 320 segments, so one more level
    "lines_pitch_10s": Case(
        "moordyn/tests/Mooring/lines.txt",
        "pitch",
        float(np.radians(3.0)),
        0.1,
        levels=(*LEVELS, 16),
    ),
}


@contextlib.contextmanager
def quiet() -> Iterator[None]:
    """Silence MoorDyn's console output (file descriptors 1 and 2)."""
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


def _option(lines: list[str], name: str) -> int | None:
    hits = [i for i, ln in enumerate(lines) if re.match(rf"^\s*\S+\s+{name}\b", ln, re.I)]
    return hits[0] if hits else None


def file_dtm(text: str) -> float:
    lines = text.splitlines()
    i = _option(lines, "dtM")
    return float(lines[i].split()[0]) if i is not None else 0.001


def refined_input(text: str, level: float, dtm: float) -> str:
    """The file with the settled relaxation, no fileIC or log, every line's NumSegs times
    ``level`` (at least 1) and ``dtM`` set."""
    lines = text.splitlines()
    for name in ("fileIC", "writeLog"):
        lines = [ln for ln in lines if not re.match(rf"^\s*\S+\s+{name}\b", ln, re.I)]
    # segments per line: the NumSegs column of the LINES table
    (head,) = [i for i, ln in enumerate(lines) if re.match(r"^\s*-+\s*LINES?\b(?! TYPE)", ln, re.I)]
    columns = [c.lower() for c in lines[head + 1].split()]
    col = columns.index("numsegs")
    i = head + 3
    while i < len(lines) and not lines[i].lstrip().startswith("-"):
        parts = lines[i].split()
        if len(parts) > col:
            parts[col] = str(max(1, int(round(int(parts[col]) * level))))
            lines[i] = "  ".join(parts)
        i += 1
    settle = [f"{dtm!r}   dtM", "1.0e-6   threshIC", "1        ICgenDynamic"]
    for name in ("dtM", "threshIC", "ICgenDynamic"):
        j = _option(lines, name)
        if j is not None:
            del lines[j]
    (opt,) = [
        i for i, ln in enumerate(lines) if re.match(r"^\s*-+.*\b(SOLVER )?OPTIONS\b", ln, re.I)
    ]
    return "\n".join([*lines[: opt + 1], *settle, *lines[opt + 1 :]]) + "\n"


def rotation(angles: np.ndarray) -> np.ndarray:
    """R = Rz(yaw) Ry(pitch) Rx(roll), exact."""
    r, p, y = angles
    cr, sr, cp, sp, cy, sy = np.cos(r), np.sin(r), np.cos(p), np.sin(p), np.cos(y), np.sin(y)
    rx = np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]])
    ry = np.array([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]])
    rz = np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]])
    return rz @ ry @ rx


def body_motion(case: Case, t: float) -> np.ndarray:
    """The six body coordinates q(t) (ramped harmonic motion of one degree of freedom)."""
    period = 1.0 / case.frequency
    t_r = RAMP_PERIODS * period
    ramp = 0.5 * (1.0 - np.cos(np.pi * t / t_r)) if t < t_r else 1.0
    q = np.zeros(6)
    q[DOFS.index(case.dof)] = case.amplitude * ramp * np.sin(2.0 * np.pi * case.frequency * t)
    return q


def coupled_layout(text: str, source: str) -> tuple[str, np.ndarray]:
    """``body`` with the body's six coordinates, or ``points`` with the coupled points'
    positions (n, 3), in MoorDyn's order."""
    from cablestudy.interchange import parse_moordyn

    md = parse_moordyn(text, source)
    bodies = [b for b in md.bodies.values() if b.attachment.lower() in ("coupled", "vessel")]
    points = sorted(
        (p for p in md.points.values() if p.attachment.lower() in ("coupled", "vessel")),
        key=lambda p: p.id,
    )
    if bodies:
        assert len(bodies) == 1 and not points, "one coupled body and nothing else"
        (b,) = bodies
        return "body", np.array([*b.position, *np.radians(b.rotation_deg)], dtype=float)
    return "points", np.array([p.position for p in points], dtype=float)


def coupled_state(case: Case, kind: str, x0: np.ndarray, t: float) -> np.ndarray:
    q = body_motion(case, t)
    if kind == "body":
        return x0 + q
    ref = np.asarray(case.reference_point)
    moved = ref + q[:3] + (x0 - ref) @ rotation(q[3:]).T
    return moved.ravel()


def end_tensions(line, n: int) -> np.ndarray:  # noqa: ANN001
    """[extrapolated A, extrapolated B, raw A, raw B] [N] of one MoorDyn line (docstring)."""
    import moordyn

    n0, n1 = (np.asarray(moordyn.GetLineNodeTen(line, j)) for j in (0, 1))
    nn, nm = (np.asarray(moordyn.GetLineNodeTen(line, j)) for j in (n, n - 1))
    if n == 1:  # one segment: nothing to extrapolate from
        a = b = float(np.linalg.norm(n0))
        return np.array([a, b, a, b])
    seg0, seg1 = np.linalg.norm(n0), np.linalg.norm(2.0 * n1 - n0)
    segn, segm = np.linalg.norm(nn), np.linalg.norm(2.0 * nm - nn)
    return np.array([1.5 * seg0 - 0.5 * seg1, 1.5 * segn - 0.5 * segm, seg0, segn])


def run(case: Case, level: float, dt_factor: float = 1.0) -> dict:
    """One MoorDyn run: per line and per period the extremes of the four end tensions,
    and the wall times."""
    import moordyn

    path = DATA / case.file
    text = path.read_text()
    kind, x0 = coupled_layout(text, case.file)
    dtm = min(file_dtm(text), file_dtm(text) / level) * dt_factor
    period = 1.0 / case.frequency
    samples = int(round(SAMPLES / dt_factor))
    dt = period / samples
    with tempfile.TemporaryDirectory() as tmp, quiet():
        copy = Path(tmp) / path.name
        copy.write_text(refined_input(text, level, dtm))
        t0, c0 = time.perf_counter(), time.process_time()
        system = moordyn.Create(str(copy))
        x_start = coupled_state(case, kind, x0, 0.0)
        assert moordyn.NCoupledDOF(system) == x_start.size
        moordyn.Init(system, x_start, np.zeros_like(x_start))
        init = time.perf_counter() - t0
        init_cpu = time.process_time() - c0
        nl = moordyn.GetNumberLines(system)
        handles = [moordyn.GetLine(system, i + 1) for i in range(nl)]
        segs = [moordyn.GetLineN(h) for h in handles]
        hi = np.full((PERIODS, nl, 4), -np.inf)
        lo = np.full((PERIODS, nl, 4), np.inf)
        stepping = 0.0
        cpu = 0.0
        x_now = x_start
        for k in range(PERIODS * samples):
            t = k * dt
            x_next = coupled_state(case, kind, x0, t + dt)
            v = (x_next - x_now) / dt
            s0, c0 = time.perf_counter(), time.process_time()
            moordyn.Step(system, x_now, v, t, dt)
            cpu += time.process_time() - c0
            stepping += time.perf_counter() - s0
            x_now = x_next
            p = k // samples
            ten = np.array([end_tensions(h, n) for h, n in zip(handles, segs, strict=True)])
            np.maximum(hi[p], ten, out=hi[p])
            np.minimum(lo[p], ten, out=lo[p])
        moordyn.Close(system)
    return {
        "level": level,
        "segments": segs,
        "dtM": dtm,
        "handover": dt,
        "init_time": init,
        "init_cpu": init_cpu,
        "step_time": stepping,
        "step_cpu": cpu,
        "time_per_simulated_second": cpu / (PERIODS * period),
        "max": hi,
        "min": lo,
    }


def extremes(r: dict, raw: bool = False) -> np.ndarray:
    """(lines, 4): max A, min A, max B, min B over the last period."""
    off = 2 if raw else 0
    hi, lo = r["max"][-1], r["min"][-1]
    return np.column_stack([hi[:, off], lo[:, off], hi[:, off + 1], lo[:, off + 1]])


def scale(e: np.ndarray) -> np.ndarray:
    """Each extreme's scale: the maximum tension at the same line end."""
    return np.repeat(e[:, 0::2], 2, axis=1)


def transient(r: dict) -> float:
    """Largest change of an extreme between the last two periods, of the line's T_max."""
    hi, lo = r["max"][:, :, :2], r["min"][:, :, :2]
    scale = hi[-1].max(axis=1)[:, None]
    change = max((np.abs(hi[-1] - hi[-2]) / scale).max(), (np.abs(lo[-1] - lo[-2]) / scale).max())
    return float(change)


def build(name: str) -> dict:
    case = CASES[name]
    runs = []
    for level in case.levels:
        r = run(case, level)
        runs.append(r)
        print(
            f"{name} k={level}: segments {r['segments']}, dtM {r['dtM']:.3g} s, "
            f"{r['time_per_simulated_second']:.3g} s/s, transient {transient(r):.1e}",
            flush=True,
        )
    finest = runs[-1]
    check = run(case, case.levels[-1], dt_factor=0.5)
    ref = extremes(finest)
    table = []
    prev = None
    for r in runs:
        e = extremes(r)
        row = {
            "level": r["level"],
            "segments": r["segments"],
            "dtM": r["dtM"],
            "handover": r["handover"],
            "extremes": e.tolist(),
            "raw_extremes": extremes(r, raw=True).tolist(),
            "error": float(np.max(np.abs(e - ref) / scale(ref))),
            "raw_error": float(np.max(np.abs(extremes(r, raw=True) - ref) / scale(ref))),
            "change_from_previous": (
                None if prev is None else float(np.max(np.abs(e - prev) / scale(e)))
            ),
            "transient": transient(r),
            "init_time": r["init_time"],
            "init_cpu": r["init_cpu"],
            "step_time": r["step_time"],
            "step_cpu": r["step_cpu"],
            "time_per_simulated_second": r["time_per_simulated_second"],
        }
        table.append(row)
        prev = e
    dt_change = float(np.max(np.abs(extremes(check) - ref) / scale(ref)))
    converged = table[-1]["change_from_previous"] < CONVERGED and dt_change < CONVERGED
    within = [row for row in table if row["error"] <= 1e-2]
    within_raw = [row for row in table if row["raw_error"] <= 1e-2]
    text = (DATA / case.file).read_text()
    names = _line_ends(text, case.file)
    return {
        "case": name,
        "file": f"tests/data/{case.file}",
        "excitation": {
            "dof": case.dof,
            "amplitude": case.amplitude,
            "amplitude_units": "rad" if case.dof in DOFS[3:] else "m",
            "frequency": case.frequency,
            "reference_point": list(case.reference_point),
            "ramp": f"(1 - cos(pi t / t_r)) / 2 over t_r = {RAMP_PERIODS:g} periods",
            "periods": PERIODS,
            "window": "the last period",
        },
        "moordyn_version": version("moordyn"),
        "moordyn_settings": (
            "file as is except ICgenDynamic 1, threshIC 1e-6, no fileIC/writeLog; "
            "level k: NumSegs x k, dtM = min(file dtM, file dtM / k); motion handed "
            f"over {SAMPLES} times a period with the secant velocity"
        ),
        "tension": (
            "end tension extrapolated from the two end segments, 1.5 T_seg0 - 0.5 T_seg1 "
            "(MoorDyn node tensions: axial stiffness + internal damping); raw_* is "
            "MoorDyn's end-node tension (the end segment's)"
        ),
        "lines": names,
        "columns": ["tension_max_a", "tension_min_a", "tension_max_b", "tension_min_b"],
        "units": "N",
        "reference": {
            col: [float(v) for v in ref[:, j]]
            for j, col in enumerate(
                ["tension_max_a", "tension_min_a", "tension_max_b", "tension_min_b"]
            )
        },
        "converged": bool(converged),
        "convergence_bar": CONVERGED,
        "time_step_check": {
            "dtM": check["dtM"],
            "handover": check["handover"],
            "change": dt_change,
        },
        "refinement": table,
        "moordyn_time_to_1pct": _time_to(within),
        "moordyn_time_to_1pct_raw": _time_to(within_raw),
        "measured": time.strftime("%Y-%m-%d", time.gmtime()),
    }


def _time_to(rows: list[dict]) -> dict | None:
    if not rows:
        return None
    row = min(rows, key=lambda r: r["time_per_simulated_second"])
    return {
        "level": row["level"],
        "segments": row["segments"],
        "time_per_simulated_second": row["time_per_simulated_second"],
        "init_cpu": row["init_cpu"],
    }


def _line_ends(text: str, source: str) -> list[dict]:
    from cablestudy.interchange import parse_moordyn

    md = parse_moordyn(text, source)
    out = []
    for line in sorted(md.lines.values(), key=lambda x: x.id):
        out.append({"id": line.id, "a": f"point{line.attach_a}", "b": f"point{line.attach_b}"})
    return out


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cases", nargs="*", default=list(CASES))
    args = parser.parse_args(argv)
    OUT.mkdir(parents=True, exist_ok=True)
    for name in args.cases:
        result = build(name)
        (OUT / f"{name}.json").write_text(json.dumps(result, indent=1) + "\n")
        print(f"{name}: converged {result['converged']}, wrote {OUT / (name + '.json')}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
