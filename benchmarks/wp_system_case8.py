"""A mooring system's restoring curve (issue 22): MoorPy's ``tests/case8.dat`` (a spar on
three polyester legs, each splitting at a free junction into two bridles to the body),
the study as a user writes it (``configs/system-spread-bridles.yaml``) with its surge
sweep widened to 1,000 positions over -20..20 m (100 with ``--quick``), through
``cablestudy run`` in a fresh process (``--no-cache``: start-up, kernel load,
validation, the three free junctions' Newton solve per position, the body's stiffness
and the netCDF write included), against MoorPy on the same positions in a plain Python
loop (``System(file=case8.dat)``, ``initialize()``, then per position
``bodyList[0].setPosition``, ``solveEquilibrium`` and the lines' end tensions), timed
in the same run.

"Error" is the largest difference of the six bridles' fairlead tensions (end B, on the
body) from MoorPy's at ``solveEquilibrium(tol=1e-10)`` (the reference, as in
``tests/validation/test_system_moorpy.py``), relative to the largest fairlead tension,
over the positions both solve. MoorPy runs its loop twice: with ``solveEquilibrium``'s
defaults (what a user calls; ``tol=0.05`` m on the junctions, which leaves about 6e-3
of the tension) and at the reference's tolerance; the table's ratio is taken at equal
error, the notes give both. MoorPy is given the study's environment (g = 9.81, 1025 kg/m^3,
100 m), which its defaults already are. Our time is the median of 3 fresh processes (1
with ``--quick``) after one untimed run (the installation's share: bytecode, numba
kernels; see ``wp_seabed_sweep``); MoorPy's loop runs once.
"""

from __future__ import annotations

import re
import statistics
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from cablestudy.bench import WorkPrecision

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
CONFIG = REPO / "configs" / "system-spread-bridles.yaml"
CASE8 = REPO / "tests" / "data" / "moorpy" / "tests" / "case8.dat"
SURGE = (-20.0, 20.0)
#: MoorPy's tolerance on the junctions' positions [m] for the reference (as the validation)
TIGHT = 1e-10
#: the study's lines in case8.dat's order (line IDs 1..9); the bridles end on the body
LINES = [
    "bridle1a",
    "bridle1b",
    "leg1",
    "bridle2a",
    "bridle2b",
    "leg2",
    "bridle3a",
    "bridle3b",
    "leg3",
]
FAIRLEADS = [name for name in LINES if name.startswith("bridle")]


def study(path: Path, n: int) -> Path:
    """The shipped study with its surge sweep widened to ``n`` positions over SURGE."""
    text = CONFIG.read_text()
    sweep = (
        f"bodies.spar.position.0: {{start: {SURGE[0]}, stop: {SURGE[1]}, num: {n}, name: surge}}"
    )
    text, count = re.subn(r"bodies\.spar\.position\.0: \{[^}]*\}", sweep, text)
    if count != 1:
        raise RuntimeError(f"{CONFIG} no longer has one surge sweep to widen")
    path.write_text(text)
    return path


def ours(path: Path) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Surge positions, fairlead tensions (surge, bridle) and status of our run."""
    import xarray as xr

    with xr.open_dataset(path) as ds:
        assert list(ds["line"].values.astype(str)) == LINES
        return (
            ds["surge"].values,
            ds["tension_b"].sel(line=FAIRLEADS).values,
            ds["status"].values,
        )


def moorpy_loop(
    surge: np.ndarray, tol: float | None = None
) -> tuple[float, float, np.ndarray, int] | None:
    """MoorPy over every surge position: (wall seconds, CPU seconds, fairlead tensions
    (surge, bridle), number of positions whose equilibrium MoorPy reports failed), with
    ``solveEquilibrium``'s defaults or, given ``tol``, that tolerance on the junctions'
    positions [m]."""
    try:
        import moorpy
    except ImportError:
        return None
    from peers import quiet_stdout  # HERE is on the path (run)

    index = [LINES.index(name) for name in FAIRLEADS]
    out = np.full((len(surge), len(FAIRLEADS)), np.nan)
    failed = 0
    with quiet_stdout():
        ms = moorpy.System(file=str(CASE8))
        ms.initialize()
        t0, c0 = time.perf_counter(), time.process_time()
        for i, x in enumerate(surge):
            ms.bodyList[0].setPosition([float(x), 0.0, 0.0, 0.0, 0.0, 0.0])
            try:
                ok = ms.solveEquilibrium() if tol is None else ms.solveEquilibrium(tol=tol)
            except Exception:  # noqa: BLE001 - a MoorPy failure is a missing point
                failed += 1
                continue
            if not ok:
                failed += 1
                continue
            lines = sorted(ms.lineList, key=lambda ln: ln.number)
            out[i] = [lines[k].TB for k in index]
        wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    return wall, cpu, out, failed


def run(quick: bool = False) -> WorkPrecision:
    sys.path.insert(0, str(HERE))
    from wp_seabed_sweep import cli_run  # same fresh-process timing as the seabed sweep

    n = 100 if quick else 1000
    wp = WorkPrecision(
        name="system_case8",
        title=f"case8 spread mooring with bridles, {n}-position surge sweep (-20..20 m)",
        error_name="largest fairlead-tension difference / largest fairlead tension",
        time_name="wall time per position, end to end [s]",
    )
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        cfg = study(folder / "case8.yaml", n)
        first = cli_run(cfg, folder / "out")[0]  # the installation's share
        runs = [cli_run(cfg, folder / "out") for _ in range(1 if quick else 3)]
        wall = statistics.median(r[0] for r in runs)
        rss = max(r[1] for r in runs)
        cpu = statistics.median(r[2] for r in runs)
        surge, tension, status = ours(folder / "out" / "system-spread-bridles.nc")
        loose, tight = moorpy_loop(surge), moorpy_loop(surge, TIGHT)
        err = float("nan")
        if loose is None or tight is None:
            wp.notes.append("MoorPy not installed (pip install '.[peers]'): its loop skipped")
        else:
            ref = tight[2]
            both = np.all(np.isfinite(ref), axis=1) & np.all(np.isfinite(tension), axis=1)
            scale = float(np.max(np.abs(ref[both])))

            def diff(values: np.ndarray) -> float:
                return float(np.max(np.abs(values[both] - ref[both])) / scale)

            err = diff(tension)
            curve = wp.curve("MoorPy System, Python loop", peer=True)
            curve.add(f"{n} positions, solveEquilibrium defaults", loose[0] / n, diff(loose[2]))
            curve.add(f"{n} positions, tol={TIGHT:g} m", tight[0] / n, err)
            mine = f"{int(np.sum(status != 0))} failed"
            wp.notes.append(
                f"{n} surge positions of case8: `cablestudy run` {wall:.2f} s end to end "
                f"({wall / n * 1e3:.1f} ms a position; median of {len(runs)} fresh "
                f"process(es): {', '.join(f'{r[0]:.2f}' for r in runs)} s, after an untimed "
                f"first run of {first:.2f} s; peak RSS {rss:.0f} MB; {mine}; CPU {cpu:.2f} s)"
            )
            for label, (t_peer, cpu_peer, theirs, failed) in (
                ("defaults (tol=0.05 m)", loose),
                (f"tol={TIGHT:g} m", tight),
            ):
                wp.notes.append(
                    f"MoorPy loop, solveEquilibrium {label}: {t_peer:.2f} s "
                    f"({t_peer / n * 1e3:.1f} ms a position, {failed} failed, CPU "
                    f"{cpu_peer:.2f} s); ours is {wall / t_peer:.2f} x its time (the issue's "
                    f"target: 0.25 x, {'met' if wall <= 0.25 * t_peer else 'not met'}), "
                    f"{cpu / cpu_peer:.2f} x in CPU time; its six fairlead tensions differ "
                    f"from ours by {np.max(np.abs(theirs[both] - tension[both])) / scale:.1e}"
                    f" of the largest ({scale / 1e3:.0f} kN) at the {int(both.sum())} "
                    "positions both solve"
                )
        wp.curve("cablestudy run (system Newton, catenary)").add(
            f"{n} positions, 21 nodes", wall / n, err
        )
    return wp


if __name__ == "__main__":
    got = run(quick="--quick" in sys.argv)
    print("\n".join(got.summary_rows()))
    print("\n".join(got.notes))
