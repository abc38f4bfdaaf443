"""Benchmark of the time-domain dynamics on the moustafa Figs. 2-5 sweep.

Prints (medians over repeats):

1. the numba compile cost: a first run in a fresh process with an empty kernel cache,
   and with the cache filled (what every later process pays);
2. the wall time of the 92-case sweep (4 amplitudes x 23 frequencies) through the
   runner with 2 worker processes (dask start-up included), default settings;
3. its accuracy: max and min tension against a reference run of the same sweep with
   four times the steps per period, twice the elements, a ten times finer tension
   resolution per step and a 20 times tighter steady-state tolerance; errors relative
   to the reference maximum tension of the case (the scale of the curve), and the
   counters (steps, Newton iterations, rejected steps, periods).

Usage: PYTHONPATH=. python benchmarks/bench_dynamics.py [--repeats 3] [--quick]
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import xarray as xr
import yaml

ROOT = Path(__file__).resolve().parents[1]
CONFIG = ROOT / "configs" / "moustafa-figs2-5.yaml"

FIRST_RUN = """
import time
t0 = time.perf_counter()
from cablestudy.analyses.evaluate import evaluate_case
from cablestudy.study.grid import expand_cases
from cablestudy.study.loader import read_study_source
src = read_study_source({config!r})
_, cases = expand_cases(src)
t1 = time.perf_counter()
rec = evaluate_case(cases[40])
t2 = time.perf_counter()
rec = evaluate_case(cases[41])
t3 = time.perf_counter()
print(t1 - t0, t2 - t1, t3 - t2)
"""


def compile_cost(cache_dir: str) -> tuple[float, float, float]:
    env = {**os.environ, "NUMBA_CACHE_DIR": cache_dir, "PYTHONPATH": str(ROOT)}
    out = subprocess.run(
        [sys.executable, "-c", FIRST_RUN.format(config=str(CONFIG))],
        env=env,
        capture_output=True,
        text=True,
        check=True,
        cwd=ROOT,
    )
    imp, first, second = (float(v) for v in out.stdout.split())
    return imp, first, second


def run_sweep(data: dict, out: Path, workers: int, scheduler: str) -> tuple[xr.Dataset, float]:
    from cablestudy.analyses.evaluate import check_supported
    from cablestudy.run.runner import run_study
    from cablestudy.study.grid import expand_grid
    from cablestudy.study.loader import parse_study_text

    src = parse_study_text(yaml.safe_dump(data, sort_keys=False), "bench")
    grid = expand_grid(src)
    check_supported(grid.cases(), src)
    t0 = time.perf_counter()
    summary = run_study(
        src, grid, out, scheduler=scheduler, workers=workers, use_cache=False, progress=False
    )
    wall = time.perf_counter() - t0
    return xr.load_dataset(summary.path), wall


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--quick", action="store_true", help="one repeat, coarser reference")
    args = parser.parse_args()
    repeats = 1 if args.quick else args.repeats
    base = yaml.safe_load(CONFIG.read_text())

    with tempfile.TemporaryDirectory() as cache:
        cold = compile_cost(cache)
        warm = compile_cost(cache)
    print("numba kernels: first case in a fresh process")
    print(
        f"  cold cache: import {cold[0]:.2f} s, first case {cold[1]:.2f} s "
        f"(compile + run), next case {cold[2] * 1e3:.1f} ms"
    )
    print(
        f"  warm cache: import {warm[0]:.2f} s, first case {warm[1]:.2f} s, "
        f"next case {warm[2] * 1e3:.1f} ms"
    )

    walls = []
    with tempfile.TemporaryDirectory() as tmp:
        for _ in range(repeats):
            ds, wall = run_sweep(base, Path(tmp), 2, "processes")
            walls.append(wall)
    print(
        f"\nFigs. 2-5 sweep, {ds.attrs['cases']} cases, 2 worker processes: median wall "
        f"{np.median(walls):.2f} s over {repeats} (all: "
        + ", ".join(f"{w:.2f}" for w in walls)
        + ")"
    )
    print(
        f"  failed {int((ds.status != 0).sum())}, not settled "
        f"{int((ds.steady_converged == 0).sum())}; sum of case wall times "
        f"{float(ds.wall_time.sum()):.2f} s"
    )
    for name in ("dynamic_steps", "newton_iterations", "rejected_steps", "periods"):
        v = ds[name].values
        print(f"  {name}: median {np.median(v):.0f}, max {np.max(v):.0f}, total {np.sum(v):.0f}")

    ref = yaml.safe_load(CONFIG.read_text())
    dyn = ref["analysis"]["dynamic"]
    dyn.update(
        {
            "points_per_period": 128 if args.quick else 256,
            "elements": 160,
            "tension_resolution": 0.02,
            "max_refinement": 8,
            "steady_tolerance": 1e-4,
            "max_periods": 120,
        }
    )
    ref["name"] = "moustafa-figs2-5-reference"
    with tempfile.TemporaryDirectory() as tmp:
        rds, rwall = run_sweep(ref, Path(tmp), 2, "processes")
    scale = rds["tension_max"].values
    err_max = np.abs(ds["tension_max"].values - rds["tension_max"].values) / scale
    err_min = np.abs(ds["tension_min"].values - rds["tension_min"].values) / scale
    print(
        f"\naccuracy against the reference ({dyn['points_per_period']} steps per period, "
        f"160 elements, tension resolution 0.02, steady tolerance 1e-4; {rwall:.1f} s):"
    )
    print(f"  max tension: median error {np.median(err_max):.2%}, worst {np.max(err_max):.2%}")
    print(f"  min tension: median error {np.median(err_min):.2%}, worst {np.max(err_min):.2%}")
    worst = np.unravel_index(np.argmax(np.maximum(err_max, err_min)), err_max.shape)
    print(
        f"  worst case: amplitude {float(ds.amplitude[worst[0]]):g} m, frequency "
        f"{float(ds.frequency[worst[1]]):g} Hz: max {float(ds.tension_max[worst]):.2f} "
        f"vs {float(rds.tension_max[worst]):.2f} N, min {float(ds.tension_min[worst]):.2f} "
        f"vs {float(rds.tension_min[worst]):.2f} N"
    )
    print(f"  reference not settled: {int((rds.steady_converged == 0).sum())}")


if __name__ == "__main__":
    main()
