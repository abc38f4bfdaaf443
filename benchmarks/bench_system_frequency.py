"""Speed of the system frequency domain (issue 24): MoorPy's case8 (spar, three legs
with bridles, free junctions; imported whole) moved in surge 2 m over a sweep of 50
frequencies from 0.02 to 0.5 Hz, each line linearised at ``--nodes`` nodes
(:mod:`cablestudy.dynamics.system_frequency`). The statics and the linear model are
built once and shared by the cases (as a sweep does); per case the drag iteration
and the band solves run. Reported: CPU time (``time.process_time``; the machine may be
shared) of the statics, of the linear model, and per case; drag iterations; and the
same cases as one sweep (:func:`cablestudy.dynamics.system_frequency_sweep.
solve_system_sweep_arrays`, as a study runs them): CPU time a case.

    PYTHONPATH=$PWD .venv/bin/python benchmarks/bench_system_frequency.py [--nodes 41]

With ``--pipeline ELEMENTS``: the same 50-case sweep of frequency through the command
line (configs/system-case8-surge.yaml as a user writes it, surge 2 m, the time domain
at its default settings) by ``method: frequency`` and by ``method: time`` in one
process: one run each to load the compiled kernels, then three runs of the sweep and
three of a one-case study, each with the analyses' caches emptied (statics and models
built again, as in a user's run); reported: medians of the CPU time a case (the
sweep's total over 50), of one more case (``(T_50 - T_1) / 49``: the per-case cost
without what a study pays once: reading, statics, model, writing) and their ratios.
"""

from __future__ import annotations

import argparse
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
CASE8 = "moorpy/tests/case8.dat"


def run(nodes: int, cases: int = 50) -> dict[str, float]:
    from cablestudy.analyses.system import system_model
    from cablestudy.dynamics.system_frequency import system_linear
    from cablestudy.dynamics.system_frequency_sweep import solve_system_sweep_arrays
    from cablestudy.interchange import import_model, imported_yaml
    from cablestudy.statics import STATIC_SOLVERS
    from cablestudy.statics.system import solve_system
    from cablestudy.study.grid import expand_cases
    from cablestudy.study.loader import parse_study_text
    from tests.system_frequency_reference import solve_system_harmonic

    path = ROOT / "tests" / "data" / CASE8
    imported = import_model(path.read_text(), CASE8, folder=path.parent)
    _, grid = expand_cases(parse_study_text(imported_yaml(imported, CASE8), "<imported>"))
    system = system_model(grid[0].study)
    system = replace(
        system,
        lines=tuple(replace(sl, problem=replace(sl.problem, n_nodes=nodes)) for sl in system.lines),
    )
    motion = np.array([[-2j, 0, 0, 0, 0, 0]])  # surge 2 sin(w t) [m]
    # warm: compiled kernels loaded (a first call in a process)
    static = solve_system(system, STATIC_SOLVERS["catenary"])
    model, why = system_linear(system, static)
    assert model is not None, why
    solve_system_harmonic(model, 0.6, motion)
    c0 = time.process_time()
    static = solve_system(system, STATIC_SOLVERS["catenary"])
    c1 = time.process_time()
    model, why = system_linear(system, static)
    assert model is not None, why
    c2 = time.process_time()
    iterations, failed = [], 0
    for f in np.linspace(0.02, 0.5, cases):
        out = solve_system_harmonic(model, 2.0 * np.pi * f, motion)
        iterations.append(out.iterations)
        failed += out.status != 0
    c3 = time.process_time()
    # the same cases as one sweep (cablestudy.dynamics.system_frequency_sweep), as a study
    # runs them
    w = 2.0 * np.pi * np.linspace(0.02, 0.5, cases)
    solve_system_sweep_arrays(model, w[:3], [motion] * 3)  # its compiled kernel loaded
    c4 = time.process_time()
    swept = solve_system_sweep_arrays(model, w, [motion] * cases)[0]
    c5 = time.process_time()
    return {
        "static": c1 - c0,
        "linear_model": c2 - c1,
        "per_case": (c3 - c2) / cases,
        "iterations_mean": float(np.mean(iterations)),
        "iterations_max": float(np.max(iterations)),
        "failed": float(failed),
        "sweep": (c5 - c4) / cases,
        "failed_sweep": float(sum(r.status != 0 for r in swept)),
    }


def _cold() -> None:
    """Empty the analyses' per-process caches (statics, line models, the system's
    linear model): a run then pays for everything a user's run pays for but the
    interpreter's start and the loading of the compiled kernels."""
    import importlib

    for name in (
        "static",
        "line_model",
        "frequency",
        "system",
        "system_dynamic",
        "system_frequency",
    ):
        module = importlib.import_module(f"cablestudy.analyses.{name}")
        for attr, value in vars(module).items():
            if "CACHE" in attr and hasattr(value, "clear"):
                value.clear()


def pipeline(
    elements: int, cases: int = 50, repeats: int = 3, keep: Path | None = None
) -> dict[str, float]:
    """CPU time a case [s] of the frequency and the time domain through the command line
    on the same sweep of ``cases`` frequencies (module docstring), medians of
    ``repeats`` runs each with the caches emptied (:func:`_cold`), after one run that
    loads the compiled kernels; and the cost of one more case, from the same runs of a
    sweep of one case (``(T_cases - T_1) / (cases - 1)``). The frequency sweep's cases
    run as arrays (:mod:`cablestudy.analyses.system_fd_grid`), counted in the first run.
    With ``keep``, each method's last ``cases``-case dataset is copied there
    (``frequency.nc``, ``time.nc``)."""
    import shutil
    import statistics
    import tempfile

    from cablestudy.cli import main as cli

    text = (ROOT / "configs" / "system-case8-surge.yaml").read_text()
    head = text[: text.index("  dynamic:")]
    out: dict[str, float] = {}
    with tempfile.TemporaryDirectory() as tmp:

        def once(method: str, n: int) -> float:
            freqs = ", ".join(f"{f:.6g}" for f in np.linspace(0.02, 0.5, n))
            cfg = Path(tmp) / f"{method}{n}.yaml"
            cfg.write_text(
                head + "  dynamic:\n"
                "    excitation: {body: body1, dof: surge, amplitude: 2.0, frequency: 0.1}\n"
                f"    method: {method}\n    elements: {elements}\n"
                f"sweep:\n  analysis.dynamic.excitation.frequency: [{freqs}]\n"
            )
            args = ["run", str(cfg), "--out", str(Path(tmp) / f"{method}{n}"), "--no-cache"]
            _cold()
            c0 = time.process_time()
            assert cli([*args, "--no-progress", "--scheduler", "synchronous"]) == 0
            return time.process_time() - c0

        from cablestudy.analyses.counters import COUNTERS

        for method in ("frequency", "time"):
            before = COUNTERS["fd_grid_cases"]
            once(method, cases)  # the compiled kernels loaded
            # the frequency sweep's cases evaluated as arrays (analyses.system_fd_grid)
            out[f"{method}_arrays"] = COUNTERS["fd_grid_cases"] - before
            full = [once(method, cases) for _ in range(repeats)]
            one = [once(method, 1) for _ in range(repeats)]
            out[method] = statistics.median(full) / cases
            out[f"{method}_marginal"] = (statistics.median(full) - statistics.median(one)) / (
                cases - 1
            )
            out[f"{method}_one"] = statistics.median(one)
            if keep is not None:
                (nc,) = (Path(tmp) / f"{method}{cases}").glob("*.nc")
                shutil.copy(nc, keep / f"{method}.nc")
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--nodes", type=int, default=41)
    parser.add_argument("--pipeline", type=int, default=0, metavar="ELEMENTS")
    args = parser.parse_args()
    if args.pipeline:
        p = pipeline(args.pipeline)
        f, t = p["frequency"], p["time"]
        fm, tm = p["frequency_marginal"], p["time_marginal"]
        print(
            f"case8 surge 2 m, 50 frequencies 0.02-0.5 Hz, {args.pipeline} elements a line, "
            f"through the command line (CPU, medians of 3 cold runs): frequency "
            f"{f * 1e3:.2f} ms a case, time {t * 1e3:.1f} ms a case: ratio {t / f:.1f}; "
            f"one more case: frequency {fm * 1e3:.2f} ms, time {tm * 1e3:.1f} ms: ratio "
            f"{tm / fm:.1f}; a study of one case: frequency {p['frequency_one'] * 1e3:.1f} ms, "
            f"time {p['time_one'] * 1e3:.1f} ms; cases run as arrays (of 50): "
            f"{p['frequency_arrays']:.0f}"
        )
        return
    r = run(args.nodes)
    print(
        f"case8 surge 2 m, 50 frequencies 0.02-0.5 Hz, {args.nodes} nodes a line: statics "
        f"{r['static'] * 1e3:.0f} ms, linear model {r['linear_model'] * 1e3:.0f} ms, "
        f"{r['per_case'] * 1e3:.1f} ms a case (CPU), drag iterations mean "
        f"{r['iterations_mean']:.1f} max {r['iterations_max']:.0f}, failed {r['failed']:.0f}; "
        f"as one sweep: {r['sweep'] * 1e3:.2f} ms a case, failed {r['failed_sweep']:.0f}"
    )


if __name__ == "__main__":
    main()
