"""Modal analysis: run time against frequency error as the mesh is refined.

Level cable, span 100 m, sag/span 1/40, lambda^2 = 100, 10 modes. The error of each
mesh is measured against the Richardson extrapolation (4 f_2N - f_N) / 3 of the two
finest meshes. Prints medians over repeats and the time ratio between meshes.

Run: PYTHONPATH=. python benchmarks/bench_modal.py
"""

from __future__ import annotations

import math
import statistics
import time

import numpy as np
from scipy.optimize import brentq

from cablestudy.dynamics.modal import ModalProblem, modal_analysis
from cablestudy.statics import (
    STATIC_SOLVERS,
    EndCondition,
    LineModel,
    Medium,
    StaticProblem,
)


def problem(elements: int) -> ModalProblem:
    l, m, g, eps, lam2 = 100.0, 1.0, 9.81, 1 / 40, 100.0
    w = m * g
    H = w * l / (8 * eps)
    EA = lam2 * H * l * (1 + 8 * eps**2) / (l * (w * l / H) ** 2)
    L0 = brentq(
        lambda L: H * L / EA + (2 * H / w) * math.asinh(w * L / (2 * H)) - l,
        0.5 * l,
        2 * l,
        xtol=1e-13,
    )

    def one(v: float) -> np.ndarray:
        return np.array([float(v)])

    line = LineModel(
        length=one(L0),
        weight=one(w),
        mass=one(m),
        axial_stiffness=one(EA),
        diameter=one(0.05),
        drag_normal=one(1.2),
        drag_tangential=one(0.0),
        added_mass_normal=one(1.0),
        added_mass_tangential=one(0.0),
        bending_stiffness=one(0.0),
        damping_ratio=one(0.0),
        attachment_s=np.zeros(0),
        attachment_force=np.zeros((0, 3)),
        attachment_mass=np.zeros(0),
        attachment_volume=np.zeros(0),
    )
    medium = Medium(density=0.0, gravity=g)
    a = EndCondition(kind="fixed", position=np.zeros(3))
    b = EndCondition(kind="fixed", position=np.array([l, 0.0, 0.0]))
    st = STATIC_SOLVERS["analytic"].solve(
        StaticProblem(line=line, medium=medium, end_a=a, end_b=b, n_nodes=elements + 1)
    )
    return ModalProblem(line=line, medium=medium, end_a=a, end_b=b, static=st, n_modes=10)


def main() -> None:
    meshes = [50, 100, 200, 400, 800, 1600, 3200]
    freqs, times = {}, {}
    for n in meshes:
        prob = problem(n)
        samples = []
        for _ in range(5):
            t0 = time.perf_counter()
            res = modal_analysis(prob)
            samples.append(time.perf_counter() - t0)
        assert res.success, res.message
        freqs[n], times[n] = res.frequency, statistics.median(samples)
    ref = (4 * freqs[meshes[-1]] - freqs[meshes[-2]]) / 3
    print("| elements | dof | median time [ms] | time ratio | max rel. error (10 modes) |")
    print("|---|---|---|---|---|")
    prev = None
    for n in meshes:
        err = float(np.max(np.abs(freqs[n] / ref - 1)))
        ratio = "" if prev is None else f"{times[n] / times[prev]:.2f}"
        print(f"| {n} | {3 * (n - 1)} | {times[n] * 1e3:.2f} | {ratio} | {err:.2e} |")
        prev = n


if __name__ == "__main__":
    main()
