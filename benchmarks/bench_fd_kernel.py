"""CPU of the system frequency domain's compiled drag iteration alone (issue 24): the
packed case8 model (MoorPy's spar, three bridled polyester legs, imported whole; surge
2 m) at ``--nodes`` nodes a line, the 50 frequencies 0.02-0.5 Hz of
``bench_system_frequency.py`` in one call of :func:`.system_fd_sweep.solve_sweep`, as a
study's sweep calls it. Reported: CPU a case (median over ``--repeats`` calls), drag
iterations a case (mean, max), and with ``--save FILE`` the answers (disp, forces,
info) for a comparison between two trees (``--compare FILE``).

    PYTHONPATH=$PWD .venv/bin/python benchmarks/bench_fd_kernel.py [--nodes 21]
"""

from __future__ import annotations

import argparse
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
CASE8 = "moorpy/tests/case8.dat"


def model_of(nodes: int):  # noqa: ANN201
    """case8's linear model at ``nodes`` nodes a line."""
    from cablestudy.analyses.system import system_model
    from cablestudy.dynamics.system_frequency import system_linear
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
    static = solve_system(system, STATIC_SOLVERS["catenary"])
    model, why = system_linear(system, static)
    assert model is not None, why
    return model


def main() -> None:
    from cablestudy.dynamics.frequency_model import DragSettings
    from cablestudy.dynamics.system_frequency import prescribed_motion, sweep_compiled

    ap = argparse.ArgumentParser()
    ap.add_argument("--nodes", type=int, default=21)
    ap.add_argument("--cases", type=int, default=50)
    ap.add_argument("--repeats", type=int, default=7)
    ap.add_argument("--save")
    ap.add_argument("--compare")
    a = ap.parse_args()
    model = model_of(a.nodes)
    motion = np.array([[-2j, 0, 0, 0, 0, 0]])
    w = 2.0 * np.pi * np.linspace(0.02, 0.5, a.cases)
    pres = np.stack([prescribed_motion(model, motion)] * a.cases)
    s = DragSettings()
    sweep_compiled(model, w[:2], pres[:2], s)  # compiled kernels loaded
    times = []
    for _ in range(a.repeats):
        c0 = time.process_time()
        disp, u_pts, forces, info, finfo = sweep_compiled(model, w, pres, s)
        times.append(time.process_time() - c0)
    it = info[:, 1]
    print(
        f"nodes {a.nodes}: kernel {1e3 * np.median(times) / a.cases:.4f} ms a case "
        f"(min {1e3 * min(times) / a.cases:.4f}); iterations mean {it.mean():.2f} "
        f"max {it.max()} total {it.sum()}; per iteration "
        f"{1e6 * np.median(times) / it.sum():.1f} us; status {np.unique(info[:, 0])}; "
        f"residual max {finfo[:, 1].max():.2e}"
    )
    if a.save:
        np.savez(a.save, disp=disp, u_pts=u_pts, forces=forces, info=info, finfo=finfo)
    if a.compare:
        ref = np.load(a.compare)
        for k in ("disp", "u_pts", "forces"):
            scale = np.max(np.abs(ref[k]), axis=tuple(range(1, ref[k].ndim)), keepdims=True)
            d = np.max(np.abs(ref[k] - locals()[k]) / scale)
            print(f"  {k}: max |diff| / case's largest {d:.2e}")
        print(f"  iterations ref mean {ref['info'][:, 1].mean():.2f}")


if __name__ == "__main__":
    main()
