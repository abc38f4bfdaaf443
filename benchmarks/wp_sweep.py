"""A static sweep end to end (issue 10): 200 spans x 100 axial stiffnesses of the Fig. 4
steel wire of the dodaran-park seed (L = 100 m, 2.466 kg/m, 20 mm, in air, B 8.6 m
below A), 20 output nodes: 20,000 catenaries through ``cablestudy run`` (a fresh
process, start-up, numba kernel load, validation, solve and netCDF write included),
against MoorPy's ``catenary`` function on the same 20,000 lines in a plain Python loop
(end forces only, ``Tol=1e-6``), timed in the same run.

"Error" here is the largest difference of the end-B tension between the two codes,
relative to that tension, over the cases both solve: the two agree to it, so the table's
ratio is MoorPy's loop time over ours at that agreement. Notes give the breakdown of our
run (start-up / validation / expansion / solve / assembly / write, from a driver in a
fresh process) and wall time and peak resident memory of the same sweep at 10,000,
100,000 and 1,000,000 cases (``--scheduler synchronous``, ``--no-cache``; 1,000,000 is
left out with ``--quick``).
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from cablestudy.bench import WorkPrecision
from cablestudy.bench import _fmt_time as _fmt

L, MASS, DIAMETER, RISE = 100.0, 2.466, 0.02, -8.6
SPANS = (50.0, 99.75)
STIFFNESS = (1.0e6, 1.0e8)

STUDY = """\
name: {name}
environment: {{fluid: air}}
line:
  segments:
    - {{length: {L}, diameter: {d}, mass_per_length: {m}, axial_stiffness: 6.283e7}}
ends:
  a: {{kind: fixed, position: [0.0, 0.0, 0.0]}}
  b: {{kind: fixed, position: [92.5, 0.0, {rise}]}}
analysis:
  static: {{nodes: 20}}
sweep:
  ends.b.position.0: {{start: {s0}, stop: {s1}, num: {n_span}, name: span}}
  line.segments.0.axial_stiffness: {{start: {e0}, stop: {e1}, num: {n_ea}}}
"""

#: a fresh process: each phase timed the way ``cablestudy run`` runs it
DRIVER = """
import json, resource, sys, time
t0 = time.perf_counter()
from cablestudy.study.loader import read_study_source, validate_data
from cablestudy.study.grid import expand_grid
from cablestudy.run.runner import run_study
t1 = time.perf_counter()
src = read_study_source(sys.argv[1])
validate_data(src.data, src)
t2 = time.perf_counter()
grid = expand_grid(src)
t3 = time.perf_counter()
summary = run_study(src, grid, sys.argv[2], scheduler="synchronous", use_cache=False,
                         progress=False)
t4 = time.perf_counter()
print(json.dumps({"start-up (imports)": t1 - t0, "validation (template)": t2 - t1,
                  "expansion (per-axis validation, grid)": t3 - t2, **summary.timings,
                  "total": t4 - t0, "failed": summary.n_failed,
                  "rss_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024}))
"""


def study(path: Path, name: str, n_span: int, n_ea: int) -> Path:
    path.write_text(
        STUDY.format(
            name=name,
            L=L,
            d=DIAMETER,
            m=MASS,
            rise=RISE,
            s0=SPANS[0],
            s1=SPANS[1],
            n_span=n_span,
            e0=STIFFNESS[0],
            e1=STIFFNESS[1],
            n_ea=n_ea,
        )
    )
    return path


def _env() -> dict[str, str]:
    env = dict(os.environ)
    root = str(Path(__file__).resolve().parents[1])
    env["PYTHONPATH"] = os.pathsep.join(p for p in (root, env.get("PYTHONPATH", "")) if p)
    return env


def run_measured(args: list[str]) -> tuple[float, str]:
    """Wall time [s] and standard output of a fresh process."""
    t0 = time.perf_counter()
    proc = subprocess.run(args, env=_env(), capture_output=True, check=False)
    wall = time.perf_counter() - t0
    if proc.returncode != 0:
        raise RuntimeError(f"{' '.join(args)} failed: {proc.stderr.decode()[-2000:]}")
    return wall, proc.stdout.decode()


def cli_run(config: Path, out: Path) -> tuple[float, float]:
    """`cablestudy run` end to end in a fresh process: wall time [s] and peak RSS [MB]."""
    cli = [sys.executable, "-m", "cablestudy", "run", str(config), "--out", str(out)]
    cli += ["--no-cache", "--no-progress", "--scheduler", "synchronous"]
    timer = Path("/usr/bin/time")
    if timer.exists():
        with tempfile.NamedTemporaryFile("r", suffix=".rss") as fh:
            wall, _ = run_measured([str(timer), "-f", "%M", "-o", fh.name, *cli])
            return wall, float(fh.read().split()[-1]) / 1024
    wall, _ = run_measured(cli)
    return wall, math.nan


def ours(path: Path) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    import xarray as xr

    with xr.open_dataset(path) as ds:
        return (
            ds["span"].values,
            ds["axial_stiffness"].values,
            ds["tension_b"].values,
        )


def moorpy_loop(spans: np.ndarray, stiffnesses: np.ndarray) -> tuple[float, np.ndarray] | None:
    """Time MoorPy's catenary over every (span, EA) pair: (seconds, end-B tensions)."""
    try:
        from moorpy.Catenary import catenary
    except ImportError:
        return None
    w = (MASS - 1.225 * math.pi * DIAMETER**2 / 4) * 9.80665  # in air, as our study
    out = np.full((len(spans), len(stiffnesses)), np.nan)
    t0 = time.perf_counter()
    for i, span in enumerate(spans):
        for j, ea in enumerate(stiffnesses):
            try:
                _, _, fbh, fbv, _ = catenary(
                    float(span), RISE, L, float(ea), w, CB=-1e3, Tol=1e-6, MaxIter=200
                )
            except Exception:  # noqa: BLE001, S112 - a MoorPy failure is a missing point
                continue
            out[i, j] = math.hypot(fbh, fbv)
    return time.perf_counter() - t0, out


def run(quick: bool = False) -> WorkPrecision:
    wp = WorkPrecision(
        name="sweep_static_20k",
        title="20,000-case static sweep end to end (200 spans x 100 EA, 20 nodes)",
        error_name="largest end-tension difference between the codes / tension",
        time_name="wall time per case, end to end [s]",
    )
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        cfg = study(folder / "sweep20k.yaml", "sweep20k", 200, 100)
        wall, rss = cli_run(cfg, folder / "out")
        span, ea, tension = ours(folder / "out" / "sweep20k.nc")
        n = tension.size
        _, phases = run_measured([sys.executable, "-c", DRIVER, str(cfg), str(folder / "driver")])
        phase = json.loads(phases.strip().splitlines()[-1])
        peer = moorpy_loop(span, ea)
        if peer is None:
            err = math.nan
            wp.notes.append("MoorPy not installed (pip install '.[peers]'): its loop skipped")
        else:
            t_peer, t_moorpy = peer
            both = np.isfinite(t_moorpy) & np.isfinite(tension)
            err = float(np.max(np.abs(t_moorpy[both] - tension[both]) / tension[both]))
            wp.curve("MoorPy catenary, Python loop", peer=True).add(
                f"{n} cases, Tol=1e-6", t_peer / n, err
            )
            wp.notes.append(
                f"20,000 cases: `cablestudy run` {wall:.2f} s end to end (fresh process, "
                f"peak RSS {rss:.0f} MB) against the MoorPy loop {t_peer:.2f} s: "
                f"{wall / t_peer:.2f} x its time (the issue's target: 0.25 x); "
                f"{int(both.sum())} cases both solve agree to {err:.1e}"
            )
        wp.curve("cablestudy run (array path)").add(f"{n} cases, 20 nodes", wall / n, err)
        order = [
            "start-up (imports)",
            "validation (template)",
            "expansion (per-axis validation, grid)",
            "solve",
            "assembly",
            "write",
        ]
        wp.notes.append(
            "breakdown of the 20,000-case run (driver in a fresh process; solve includes "
            "loading the compiled kernels): "
            + ", ".join(f"{k} {_fmt(phase[k])}" for k in order if k in phase)
            + f"; total {_fmt(phase['total'])}"
        )
        scales = [(100, 100), (1000, 100)] + ([] if quick else [(1000, 1000)])
        rows = []
        for n_span, n_ea in scales:
            cfg = study(folder / f"s{n_span * n_ea}.yaml", f"s{n_span * n_ea}", n_span, n_ea)
            wall_n, rss_n = cli_run(cfg, folder / "scale")
            rows.append(f"{n_span * n_ea:,} cases {wall_n:.1f} s, peak RSS {rss_n:.0f} MB")
            (folder / "scale" / f"s{n_span * n_ea}.nc").unlink()
        wp.notes.append(
            "scaling (`cablestudy run --scheduler synchronous --no-cache`, 20 nodes): "
            + "; ".join(rows)
        )
    return wp
