"""Agreement of two static solvers on drag-loaded 3D cases (default: the semi-analytic
``catenary`` method against the ``shooting`` method), as the output-node count grows.

Prints, per case and node count, the largest differences relative to the line length
(positions, laid length) and to the largest tension (tensions, end forces), and both
wall times. A solver that lists a case's features as unsupported is reported, not run.
Usage::

    PYTHONPATH=. python benchmarks/compare_static_solvers.py [--nodes 101 401 1601]
        [--methods catenary shooting]
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from cablestudy.statics import (  # noqa: E402
    STATIC_SOLVERS,
    EndCondition,
    LineModel,
    Medium,
    StaticProblem,
)
from cablestudy.study.grid import expand_cases  # noqa: E402
from cablestudy.study.loader import read_study_source  # noqa: E402
from cablestudy.study.problem import static_problem  # noqa: E402


def _line(
    lengths: list[float],
    w: list[float],
    ea: list[float],
    d: float,
    att: tuple[tuple[float, tuple[float, float, float]], ...] = (),
) -> LineModel:
    n = len(lengths)

    def col(v: list[float] | float) -> np.ndarray:
        return np.broadcast_to(np.asarray(v, float), (n,)).copy()

    return LineModel(
        length=col(lengths),
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
        attachment_s=np.array([a[0] for a in att], float),
        attachment_force=np.array([a[1] for a in att], float).reshape(-1, 3),
        attachment_mass=np.zeros(len(att)),
        attachment_volume=np.zeros(len(att)),
    )


def _medium(**kw: float) -> Medium:
    h = np.radians([120.0, 60.0, 0.0])
    sp = np.array([0.2, 0.6, 1.0])
    return Medium(
        density=1025.0,
        gravity=9.80665,
        current_z=np.array([-300.0, -150.0, 0.0]),
        current_velocity=np.stack([sp * np.cos(h), sp * np.sin(h), 0 * sp], 1),
        **kw,
    )


def _end(kind: str, v: list[float], z: float | None = None) -> EndCondition:
    if kind == "fixed":
        return EndCondition(kind="fixed", position=np.asarray(v, float))
    if kind == "force":
        return EndCondition(kind="force", force=np.asarray(v, float))
    return EndCondition(kind="mooring", force=np.array([v[0], v[1], 0.0]), z=z)


def cases() -> dict[str, StaticProblem]:
    out = {
        "fixed-fixed, turning current": StaticProblem(
            line=_line([400.0], [25.0], [5e7], 0.08),
            medium=_medium(),
            end_a=_end("fixed", [0, 0, -300]),
            end_b=_end("fixed", [250, 0, 0]),
        ),
        "two segments and a buoy": StaticProblem(
            line=_line(
                [250.0, 150.0], [40.0, 15.0], [3e8, 5e7], 0.06, ((250.0, (0.0, 0.0, 2000.0)),)
            ),
            medium=_medium(),
            end_a=_end("fixed", [0, 0, -280]),
            end_b=_end("fixed", [260, 40, -5]),
        ),
        "towing (force end)": StaticProblem(
            line=_line([300.0], [20.0], [1e8], 0.05),
            medium=_medium(),
            end_a=_end("fixed", [0, 0, 0]),
            end_b=_end("force", [100, 50, -500]),
        ),
        "mooring end": StaticProblem(
            line=_line([300.0], [20.0], [1e8], 0.05),
            medium=_medium(),
            end_a=_end("fixed", [0, 0, -250]),
            end_b=_end("mooring", [2000, 500], 0.0),
        ),
        "touchdown with friction": StaticProblem(
            line=_line([600.0], [200.0], [1e9], 0.1),
            medium=_medium(depth=200.0, friction=0.5),
            end_a=_end("fixed", [0, 0, -200]),
            end_b=_end("fixed", [500, 100, 0]),
        ),
        "sloped seabed": StaticProblem(
            line=_line([600.0], [200.0], [1e9], 0.1),
            medium=_medium(
                depth=200.0, friction=0.5, seabed_slope=math.radians(4.0), seabed_heading=0.5
            ),
            end_a=_end("fixed", [0, 0, -200]),
            end_b=_end("fixed", [500, 100, 0]),
        ),
    }
    for name in ("vaz-patel-segmented-mooring", "vaz-patel-turning-current"):
        src = read_study_source(ROOT / "configs" / f"{name}.yaml")
        _, study_cases = expand_cases(src)
        for case in study_cases:
            out[f"{name}{list(case.index)}"] = static_problem(case.study)
    return out


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--nodes", type=int, nargs="+", default=[101, 401, 1601])
    parser.add_argument("--methods", nargs=2, default=["catenary", "shooting"])
    args = parser.parse_args()
    m1, m2 = args.methods
    print(
        f"| case | nodes | {m1} [s] | {m2} [s] | position / L | tension / T_max "
        "| end forces / T_max | laid length / L |"
    )
    print("|---|---|---|---|---|---|---|---|")
    for name, base in cases().items():
        missing = STATIC_SOLVERS[m1].unsupported(base) + STATIC_SOLVERS[m2].unsupported(base)
        if missing:
            print(f"| {name} | - | unsupported: {'; '.join(missing)} |||||")
            continue
        for n in args.nodes:
            problem = dataclasses.replace(base, n_nodes=n, tolerance=1e-12)
            t0 = time.perf_counter()
            a = STATIC_SOLVERS[m1].solve(problem)
            t1 = time.perf_counter()
            b = STATIC_SOLVERS[m2].solve(problem)
            t2 = time.perf_counter()
            if not (a.success and b.success):
                print(
                    f"| {name} | {n} | status {a.status}: {a.message} | status {b.status}: "
                    f"{b.message} |||||"
                )
                continue
            L = problem.line.total_length
            T = float(np.max(b.tension))
            # nodes exactly at attachments hold the tension on one side: compare the rest
            smooth = ~np.isin(a.s, problem.line.attachment_s)
            dpos = np.max(np.abs(a.position - b.position)) / L
            dten = np.max(np.abs(a.tension - b.tension)[smooth]) / T
            dfor = (
                max(np.max(np.abs(a.force_a - b.force_a)), np.max(np.abs(a.force_b - b.force_b)))
                / T
            )
            dlaid = abs(a.laid_length - b.laid_length) / L
            print(
                f"| {name} | {n} | {t1 - t0:.3f} | {t2 - t1:.3f} | {dpos:.1e} | {dten:.1e} "
                f"| {dfor:.1e} | {dlaid:.1e} |"
            )


if __name__ == "__main__":
    main()
