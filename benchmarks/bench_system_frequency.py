"""Speed of the system frequency domain (issue 24): MoorPy's case8 (spar, three legs
with bridles, free junctions; imported whole) moved in surge 2 m over a sweep of 50
frequencies from 0.02 to 0.5 Hz, each line linearised at ``--nodes`` nodes
(:mod:`cablestudy.dynamics.system_frequency`). The statics and the linear model are
built once and shared by the cases (as a sweep does); per case the drag iteration
and the band solves run. Reported: CPU time (``time.process_time``; the machine may be
shared) of the statics, of the linear model, and per case; drag iterations.

    PYTHONPATH=$PWD .venv/bin/python benchmarks/bench_system_frequency.py [--nodes 41]

With ``--pipeline ELEMENTS``: the same 50-case sweep of frequency through the command
line (configs/system-case8-surge.yaml, surge 2 m, the time domain at its default
settings) by ``method: frequency`` and by ``method: time`` in one process, each run
twice (the first loads the compiled kernels); reported: CPU time a case of the second
runs and their ratio.
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
    from cablestudy.dynamics.system_frequency import solve_system_harmonic, system_linear
    from cablestudy.interchange import import_model, imported_yaml
    from cablestudy.statics import STATIC_SOLVERS
    from cablestudy.statics.system import solve_system
    from cablestudy.study.grid import expand_cases
    from cablestudy.study.loader import parse_study_text

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
    return {
        "static": c1 - c0,
        "linear_model": c2 - c1,
        "per_case": (c3 - c2) / cases,
        "iterations_mean": float(np.mean(iterations)),
        "iterations_max": float(np.max(iterations)),
        "failed": float(failed),
    }


def pipeline(elements: int, cases: int = 50) -> dict[str, float]:
    """CPU time a case [s] of the frequency and the time domain through the command line
    on the same sweep of ``cases`` frequencies (module docstring)."""
    import tempfile

    from cablestudy.cli import main as cli

    text = (ROOT / "configs" / "system-case8-surge.yaml").read_text()
    head = text[: text.index("  dynamic:")]
    freqs = ", ".join(f"{f:.6g}" for f in np.linspace(0.02, 0.5, cases))
    out: dict[str, float] = {}
    with tempfile.TemporaryDirectory() as tmp:
        for method in ("frequency", "time", "frequency", "time"):
            cfg = Path(tmp) / f"{method}.yaml"
            cfg.write_text(
                head + "  dynamic:\n"
                "    excitation: {body: body1, dof: surge, amplitude: 2.0, frequency: 0.1}\n"
                f"    method: {method}\n    elements: {elements}\n"
                f"sweep:\n  analysis.dynamic.excitation.frequency: [{freqs}]\n"
            )
            args = ["run", str(cfg), "--out", str(Path(tmp) / method), "--no-cache"]
            c0 = time.process_time()
            assert cli([*args, "--no-progress", "--scheduler", "synchronous"]) == 0
            out[method] = (time.process_time() - c0) / cases
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--nodes", type=int, default=41)
    parser.add_argument("--pipeline", type=int, default=0, metavar="ELEMENTS")
    args = parser.parse_args()
    if args.pipeline:
        p = pipeline(args.pipeline)
        print(
            f"case8 surge 2 m, 50 frequencies 0.02-0.5 Hz, {args.pipeline} elements a line, "
            f"through the command line: frequency {p['frequency'] * 1e3:.1f} ms a case, time "
            f"{p['time'] * 1e3:.1f} ms a case (CPU): ratio {p['time'] / p['frequency']:.1f}"
        )
        return
    r = run(args.nodes)
    print(
        f"case8 surge 2 m, 50 frequencies 0.02-0.5 Hz, {args.nodes} nodes a line: statics "
        f"{r['static'] * 1e3:.0f} ms, linear model {r['linear_model'] * 1e3:.0f} ms, "
        f"{r['per_case'] * 1e3:.1f} ms a case (CPU), drag iterations mean "
        f"{r['iterations_mean']:.1f} max {r['iterations_max']:.0f}, failed {r['failed']:.0f}"
    )


if __name__ == "__main__":
    main()
