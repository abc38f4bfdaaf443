"""Run time against error of the shooting static solver (``method: shooting``).

For a set of cases (exact catenary, drag-loaded 3D lines, touchdown with friction, the
vaz-patel example studies) and integration tolerances rtol, prints the median wall time
over repeats, the Newton iterations and the error against the rtol = 1e-13 solution (or
the exact catenary where there is one), relative to the line length (positions) and the
largest tension (forces). Usage::

    PYTHONPATH=. python benchmarks/bench_shooting.py [--quick]
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from cablestudy.statics import EndCondition, LineModel, Medium, StaticProblem  # noqa: E402
from cablestudy.statics.elastic_catenary import solve_between  # noqa: E402
from cablestudy.statics.shooting import ShootingSolver  # noqa: E402
from cablestudy.study.grid import expand_cases  # noqa: E402
from cablestudy.study.loader import read_study_source  # noqa: E402
from cablestudy.study.problem import static_problem  # noqa: E402


def _line(lengths: list[float], w: float, ea: float, d: float = 0.08) -> LineModel:
    n = len(lengths)

    def col(v: float) -> np.ndarray:
        return np.full(n, float(v))

    return LineModel(
        length=np.asarray(lengths, float),
        weight=col(w),
        mass=col(1.0),
        axial_stiffness=col(ea),
        diameter=col(d),
        drag_normal=col(1.2),
        drag_tangential=col(0.01),
        added_mass_normal=col(1.0),
        added_mass_tangential=col(0.0),
        bending_stiffness=col(0.0),
        damping_ratio=col(0.0),
        attachment_s=np.zeros(0),
        attachment_force=np.zeros((0, 3)),
        attachment_mass=np.zeros(0),
        attachment_volume=np.zeros(0),
    )


def _fixed(p: list[float]) -> EndCondition:
    return EndCondition(kind="fixed", position=np.asarray(p, float))


def _current() -> dict[str, np.ndarray]:
    h = np.radians([120.0, 60.0, 0.0])
    sp = np.array([0.2, 0.6, 1.0])
    return {
        "current_z": np.array([-300.0, -150.0, 0.0]),
        "current_velocity": np.stack([sp * np.cos(h), sp * np.sin(h), 0 * sp], 1),
    }


def cases() -> dict[str, StaticProblem]:
    out = {
        "catenary (exact)": StaticProblem(
            line=_line([150.0], 30.0, 1e8),
            medium=Medium(density=0.0, gravity=9.80665),
            end_a=_fixed([0, 0, 0]),
            end_b=_fixed([80.0, 0.0, -10.0]),
            n_nodes=101,
        ),
        "3D drag, turning current": StaticProblem(
            line=_line([400.0], 25.0, 5e7),
            medium=Medium(density=1025.0, gravity=9.80665, **_current()),
            end_a=_fixed([0, 0, -300]),
            end_b=_fixed([250, 0, 0]),
            n_nodes=101,
        ),
        "touchdown, friction, drag": StaticProblem(
            line=_line([600.0], 200.0, 1e9, d=0.1),
            medium=Medium(density=1025.0, gravity=9.80665, depth=200.0, friction=0.5, **_current()),
            end_a=_fixed([0, 0, -200]),
            end_b=_fixed([500, 100, 0]),
            n_nodes=101,
        ),
    }
    for name in ("vaz-patel-segmented-mooring", "vaz-patel-turning-current"):
        src = read_study_source(ROOT / "configs" / f"{name}.yaml")
        _, study_cases = expand_cases(src)
        out[f"{name} (case 1)"] = static_problem(study_cases[1].study)
    return {k: dataclasses.replace(p, tolerance=1e-12) for k, p in out.items()}


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    repeats = 1 if args.quick else 5
    print(
        "| case | rtol | median time [s] | Newton iterations | position error / L "
        "| tension error / T_max |"
    )
    print("|---|---|---|---|---|---|")
    for name, problem in cases().items():
        L = problem.line.total_length
        if name.endswith("(exact)"):
            assert problem.end_a.position is not None and problem.end_b.position is not None
            ref = solve_between(
                problem.end_a.position,
                problem.end_b.position,
                L,
                float(problem.line.weight[0]),
                float(problem.line.axial_stiffness[0]),
                np.linspace(0.0, L, problem.n_nodes),
                tolerance=1e-14,
            )
        else:
            ref = ShootingSolver(rtol=1e-13).solve(problem)
        for rtol in (1e-8, 1e-10, 1e-12):
            solver = ShootingSolver(rtol=rtol)
            times = []
            for _ in range(repeats):
                t0 = time.perf_counter()
                res = solver.solve(problem)
                times.append(time.perf_counter() - t0)
            dpos = np.max(np.abs(res.position - ref.position)) / L
            dten = np.max(np.abs(res.tension - ref.tension)) / np.max(ref.tension)
            print(
                f"| {name} | {rtol:.0e} | {np.median(times):.3f} | {res.iterations} "
                f"| {dpos:.1e} | {dten:.1e} |"
            )


if __name__ == "__main__":
    main()
