"""Benchmark of the semi-analytic static solver (method 'catenary').

Run from the repository root:

    PYTHONPATH=. python benchmarks/bench_statics.py [--quick]

Prints medians (over repeats) of the time per case, and the accuracy reached, for

1. a single-segment still-water catenary to tolerance 1e-9, many cases in one task:
   the batch path (compiled, and numpy), the one-by-one solver, Irvine's exact solver
   (method 'analytic'), MoorPy's catenary (if installed), and the whole chunk
   evaluation from validated study cases (config conversion, solve, records);
2. a 100-element drag-loaded 3D solve (sheared, turning current), and a drag-dominated
   light tether (2 m/s, drag ~100 x weight), with drag iterations and final residual;
3. the dodaran-park figure studies: iterations and residual per case.
"""

from __future__ import annotations

import argparse
import math
import statistics
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

from cablestudy.statics import EndCondition, LineModel, Medium, StaticProblem
from cablestudy.statics.batch import solve_batch
from cablestudy.statics.elastic_catenary import solve_between
from cablestudy.statics.semi_analytic import SemiAnalyticSolver

ROOT = Path(__file__).resolve().parents[1]
W_STEEL = 2.466 * 9.80665  # seed Fig. 4 line in air [N/m]
EA_STEEL = 6.283e7  # [N]


def median_time(fn: Callable[[], object], *, repeats: int, per: int) -> float:
    """Median over ``repeats`` runs of the wall time of ``fn()`` divided by ``per``."""
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append((time.perf_counter() - t0) / per)
    return statistics.median(times)


def line(L: float, w: float, EA: float, *, d: float = 0.02) -> LineModel:
    one = np.ones(1)
    return LineModel(
        length=L * one,
        weight=w * one,
        mass=w / 9.80665 * one,
        axial_stiffness=EA * one,
        diameter=d * one,
        drag_normal=1.2 * one,
        drag_tangential=0.01 * one,
        added_mass_normal=one,
        added_mass_tangential=0 * one,
        bending_stiffness=0 * one,
        damping_ratio=0 * one,
        attachment_s=np.zeros(0),
        attachment_force=np.zeros((0, 3)),
        attachment_mass=np.zeros(0),
        attachment_volume=np.zeros(0),
    )


def still_water_cases(n: int, seed: int = 0) -> list[StaticProblem]:
    """The seed's Fig. 4 line (L = 100 m in air) with end B spread around (92.5, -8.6)."""
    rng = np.random.default_rng(seed)
    air = Medium(density=1.225, gravity=9.80665)
    return [
        StaticProblem(
            line=line(100.0, W_STEEL, EA_STEEL),
            medium=air,
            end_a=EndCondition(kind="fixed", position=np.zeros(3)),
            end_b=EndCondition(
                kind="fixed",
                position=np.array([rng.uniform(60.0, 99.0), 0.0, rng.uniform(-20.0, 20.0)]),
            ),
            n_nodes=101,
            tolerance=1e-9,
        )
        for _ in range(n)
    ]


def bench_still_water(n: int, repeats: int) -> list[str]:
    probs = still_water_cases(n)
    solver = SemiAnalyticSolver()
    out = []
    solve_batch(probs[:4])  # compile (numba caches on disk) outside the timing
    t_batch = median_time(lambda: solve_batch(probs), repeats=repeats, per=n)
    res = solve_batch(probs)
    exact = [
        solve_between(np.zeros(3), p.end_b.position, 100.0, W_STEEL, EA_STEEL, r.s, tolerance=1e-13)
        for p, r in zip(probs, res, strict=True)
    ]
    ferr = max(
        float(np.max(np.abs(r.force_a - e.force_a)) / np.max(np.abs(e.force_a)))
        for r, e in zip(res, exact, strict=True)
    )
    perr = max(
        float(np.max(np.abs(r.position - e.position))) / 100.0
        for r, e in zip(res, exact, strict=True)
    )
    iters = [r.iterations for r in res]
    out.append(f"still water, single segment, tolerance 1e-9, {n} cases in one task, 101 nodes:")
    out.append(
        f"  batch (compiled kernel)      median {t_batch * 1e6:8.1f} us/case   "
        f"max rel. error vs Irvine: force {ferr:.1e}, position {perr:.1e}; "
        f"Newton iterations median {statistics.median(iters):.0f}, max {max(iters)}"
    )
    m = min(n, 200)
    t_one = median_time(lambda: [solver.solve(p) for p in probs[:m]], repeats=repeats, per=m)
    out.append(f"  one by one (solver.solve)    median {t_one * 1e6:8.1f} us/case")
    t_irv = median_time(
        lambda: [
            solve_between(
                np.zeros(3), p.end_b.position, 100.0, W_STEEL, EA_STEEL, np.linspace(0, 100, 101)
            )
            for p in probs[:m]
        ],
        repeats=repeats,
        per=m,
    )
    out.append(f"  Irvine exact ('analytic')    median {t_irv * 1e6:8.1f} us/case")
    try:
        from moorpy.Catenary import catenary
    except ImportError:
        out.append("  MoorPy: not installed (pip install moorpy) - skipped")
    else:

        def moorpy_all() -> None:
            for p in probs[:m]:
                b = p.end_b.position
                # MoorPy's frame: anchor at the lower end, fairlead above; CB < 0 is the
                # anchor's height above the seabed (here: no seabed contact)
                catenary(
                    float(b[0]),
                    float(-b[2]),
                    100.0,
                    EA_STEEL,
                    W_STEEL,
                    CB=-1000.0,
                    Tol=1e-9,
                    nNodes=101,
                )

        t_mp = median_time(moorpy_all, repeats=repeats, per=m)
        out.append(
            f"  MoorPy catenary (Tol 1e-9)   median {t_mp * 1e6:8.1f} us/case   "
            f"ratio MoorPy / batch = {t_mp / t_batch:.1f}"
        )
    out.append(
        f"  ratio one-by-one / batch = {t_one / t_batch:.1f}, "
        f"Irvine / batch = {t_irv / t_batch:.1f}"
    )
    return out


def bench_chunk(n: int, repeats: int) -> list[str]:
    """Whole chunk evaluation from a validated study (what the runner's task does)."""
    from cablestudy.analyses.evaluate import evaluate_case, evaluate_chunk
    from cablestudy.analyses.static import _STATIC_CACHE
    from cablestudy.study.grid import expand_cases
    from cablestudy.study.loader import read_study_source

    src = read_study_source(ROOT / "configs" / "dodaran-fig4-semi-analytic.yaml")
    src.data["analysis"]["static"]["tolerance"] = 1e-9
    src.data["sweep"] = {
        "ends.b.position.0": {"start": 60.0, "stop": 99.0, "num": n, "name": "span"}
    }
    _, cases = expand_cases(src)

    def run() -> None:
        _STATIC_CACHE.clear()
        evaluate_chunk(cases)

    t_chunk = median_time(run, repeats=repeats, per=len(cases))

    def run_one() -> None:
        _STATIC_CACHE.clear()
        for c in cases:
            evaluate_case(c)

    t_single = median_time(run_one, repeats=max(1, repeats // 2), per=len(cases))
    return [
        f"chunk of {len(cases)} study cases (config -> problem -> solve -> record):",
        f"  evaluate_chunk (batched)     median {t_chunk * 1e6:8.1f} us/case",
        f"  evaluate_case one by one     median {t_single * 1e6:8.1f} us/case",
    ]


def bench_drag(repeats: int) -> list[str]:
    solver = SemiAnalyticSolver()
    out = ["drag-loaded 3D solves, 100 drag elements, tolerance 1e-9:"]
    sheared = Medium(
        density=1025.0,
        gravity=9.80665,
        current_z=np.array([-300.0, 0.0]),
        current_velocity=np.array([[0.0, 0.3, 0.0], [0.514, 0.0, 0.0]]),
    )
    cases = {
        "fig. 6 cable (340 m, 2.25 N/m), sheared turning current 0.514 -> 0.3 m/s": StaticProblem(
            line=line(340.0, 2.25, EA_STEEL),
            medium=sheared,
            end_a=EndCondition(kind="fixed", position=np.zeros(3)),
            end_b=EndCondition(kind="fixed", position=np.array([150.0, 0, -250.0])),
            n_nodes=101,
            tolerance=1e-9,
        ),
        "light tether 100 m, 0.5 N/m, 2 m/s at 30 deg (drag ~100 x weight)": StaticProblem(
            line=line(100.0, 0.5, 1e6),
            medium=Medium(
                density=1025.0,
                gravity=9.80665,
                current_z=np.array([0.0]),
                current_velocity=np.array([[2.0 * math.cos(0.5236), 2.0 * math.sin(0.5236), 0]]),
            ),
            end_a=EndCondition(kind="fixed", position=np.zeros(3)),
            end_b=EndCondition(kind="fixed", position=np.array([60.0, 0, -10.0])),
            n_nodes=101,
            tolerance=1e-9,
        ),
        "towed 500 m cable, 10 N/m, free end, 1.5 m/s": StaticProblem(
            line=line(500.0, 10.0, 1e8, d=0.05),
            medium=Medium(
                density=1025.0,
                gravity=9.80665,
                current_z=np.array([0.0]),
                current_velocity=np.array([[1.5, 0.0, 0.0]]),
            ),
            end_a=EndCondition(kind="fixed", position=np.zeros(3)),
            end_b=EndCondition(kind="force", force=np.zeros(3)),
            n_nodes=101,
            tolerance=1e-9,
        ),
    }
    for name, prob in cases.items():
        res = solver.solve(prob)
        t = median_time(lambda prob=prob: solver.solve(prob), repeats=repeats, per=1)
        out.append(
            f"  {name}:\n    median {t * 1e3:6.1f} ms, status {res.status}, drag iterations "
            f"{res.drag_iterations}, Newton iterations {res.iterations}, final residual "
            f"{res.residual:.1e}"
        )
    return out


def bench_figures() -> list[str]:
    from cablestudy.analyses.evaluate import evaluate_case
    from cablestudy.analyses.static import _STATIC_CACHE
    from cablestudy.study.grid import expand_cases
    from cablestudy.study.loader import read_study_source

    out = [
        "dodaran-park figure studies (per case: status, drag iterations, Newton iterations, "
        "residual):"
    ]
    for name in (
        "dodaran-fig4-semi-analytic",
        "dodaran-fig5-point-load",
        "dodaran-fig6-marine-cable-340",
        "dodaran-fig7-marine-cable-310",
        "dodaran-fig8-submersible-3d",
    ):
        _, cases = expand_cases(read_study_source(ROOT / "configs" / f"{name}.yaml"))
        _STATIC_CACHE.clear()
        for case in cases:
            rec = evaluate_case(case)
            d = rec.data
            out.append(
                f"  {name} {dict((k, round(float(v), 4)) for k, v in case.coords.items())}: "
                f"status {rec.status}, drag {int(d['drag_iterations'])}, Newton "
                f"{int(d['static_iterations'])}, residual "
                f"{float(d['static_residual']):.1e}, {rec.wall_time * 1e3:.1f} ms"
            )
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer cases and repeats")
    args = parser.parse_args()
    n, repeats = (500, 3) if args.quick else (4000, 7)
    lines = [
        *bench_still_water(n, repeats),
        *bench_chunk(n // 4, repeats),
        *bench_drag(repeats),
        *bench_figures(),
    ]
    print("\n".join(lines))


if __name__ == "__main__":
    main()
