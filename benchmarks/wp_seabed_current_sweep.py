"""A line resting on the seabed in a current, swept (issue 20, deliver 2): the chain of
``wp_seabed_sweep`` (300 m, 76 mm, 126 kg/m, EA 5e8 N, C_N 2.4, C_T 0.4) from an anchor on
a flat seabed in 100 m of water (friction 0.5) to a fairlead 10 m below the surface, in
a uniform current heading 30 deg, 100 current speeds (0.1-1.5 m/s) x 200 fairlead
offsets (215-275 m), 20 output nodes (20 drag elements), the study written as a user
writes it (no ``method`` key): 20,000 lines through ``cablestudy run`` in a fresh
process, CPU time (user + system; the machine is shared), median of 3 after an untimed
first run, against the case-by-case path (the general solver and its verification,
:meth:`cablestudy.statics.semi_analytic.SemiAnalyticSolver.solve` with
``compiled=False`` and :func:`cablestudy.statics.verify.verified`, which the grid ran
for each of these lines before the drag iteration with seabed contact was compiled) on
500 cases drawn at random from the grid, its CPU time scaled to 20,000.

"Error" is the largest fairlead-tension difference between the two paths over those 500
cases, relative to that tension: the kernel runs the general solver's drag iteration
step for step, so it is round-off.
"""

from __future__ import annotations

import statistics
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from cablestudy.bench import WorkPrecision

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from wp_seabed_sweep import DEPTH, DIAMETER, FAIRLEAD, MASS, MU, OFFSETS, L, cli_run  # noqa: E402

SPEEDS = (0.1, 1.5)
SUBSET = 500

STUDY = """\
name: {name}
environment:
  fluid: water
  depth: {depth}
  seabed: {{friction: {mu}}}
  current: [{{z: 0.0, speed: 0.5, heading_deg: 30.0}}]
line:
  segments:
    - {{length: {L}, diameter: {d}, mass_per_length: {m}, axial_stiffness: 5.0e8,
       drag_normal: 2.4, drag_tangential: 0.4}}
ends:
  a: {{kind: fixed, position: [0.0, 0.0, {za}]}}
  b: {{kind: fixed, position: [250.0, 0.0, {zb}]}}
analysis:
  static: {{nodes: 20}}
sweep:
  environment.current.0.speed: {{start: {v0}, stop: {v1}, num: {n_v}, name: current_speed}}
  ends.b.position.0: {{start: {x0}, stop: {x1}, num: {n_x}, name: offset}}
"""


def study(path: Path, name: str, n_v: int, n_x: int) -> Path:
    path.write_text(
        STUDY.format(
            name=name,
            depth=DEPTH,
            mu=MU,
            L=L,
            d=DIAMETER,
            m=MASS,
            za=-DEPTH,
            zb=FAIRLEAD,
            v0=SPEEDS[0],
            v1=SPEEDS[1],
            n_v=n_v,
            x0=OFFSETS[0],
            x1=OFFSETS[1],
            n_x=n_x,
        )  # fmt: skip
    )
    return path


def case_by_case(config: Path, rows: np.ndarray) -> tuple[float, np.ndarray, np.ndarray]:
    """The general solver and its verification on the grid's cases ``rows`` (flat
    indices): (CPU seconds, fairlead tensions [N], statuses)."""
    from cablestudy.statics.semi_analytic import SemiAnalyticSolver
    from cablestudy.statics.verify import verified
    from cablestudy.study.grid import expand_grid
    from cablestudy.study.loader import read_study_source, validate_data
    from cablestudy.study.problem import static_problem

    src = read_study_source(str(config))
    validate_data(src.data, src)
    grid = expand_grid(src)
    problems = [static_problem(grid.study_at(np.unravel_index(i, grid.shape))) for i in rows]
    solver = SemiAnalyticSolver()
    c0 = time.process_time()
    got = [verified(p, solver.solve(p, compiled=False), method="catenary") for p in problems]
    cpu = time.process_time() - c0
    tension = np.array([float(np.linalg.norm(r.force_b)) for r in got])
    return cpu, tension, np.array([r.status for r in got])


def run(quick: bool = False) -> WorkPrecision:
    wp = WorkPrecision(
        name="sweep_seabed_current_20k",
        title="20,000 chains on the seabed in a current (100 speeds x 200 offsets, friction 0.5)",
        error_name="largest fairlead-tension difference from the case-by-case path / tension",
        time_name="CPU time per case, end to end [s]",
    )
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        cfg = study(folder / "current20k.yaml", "current20k", 100, 200)
        first = cli_run(cfg, folder / "out")[2]  # the installation's share
        runs = [cli_run(cfg, folder / "out") for _ in range(1 if quick else 3)]
        cpu = statistics.median(r[2] for r in runs)
        import xarray as xr

        with xr.open_dataset(folder / "out" / "current20k.nc") as ds:
            tension = ds["tension_b"].values.ravel()
            status = ds["status"].values.ravel()
            fallback = int(ds.attrs.get("cases_fallback", 0))
            reasons = ds.attrs.get("fallback_reasons", "")
        n = tension.size
        rows = np.sort(np.random.default_rng(20).choice(n, SUBSET // (10 if quick else 1), False))
        cpu_one, t_one, st_one = case_by_case(cfg, rows)
        both = (st_one == 0) & (status[rows] == 0)
        err = float(np.max(np.abs(t_one[both] - tension[rows][both]) / t_one[both]))
        per = cpu_one / rows.size
        wp.curve("case by case (general solver, verified)", peer=True).add(
            f"{rows.size} of the cases, scaled", per, err
        )
        wp.curve("cablestudy run (drag iteration with seabed contact, compiled)").add(
            f"{n} cases, 20 nodes", cpu / n, err
        )
        wp.notes.append(
            f"{n} chains on the seabed in a current: `cablestudy run` {cpu:.2f} s CPU end to "
            f"end (median of {len(runs)} fresh processes: "
            f"{', '.join(f'{r[2]:.2f}' for r in runs)} s CPU, wall "
            f"{', '.join(f'{r[0]:.2f}' for r in runs)} s, after an untimed first run of "
            f"{first:.2f} s CPU; {int(np.sum(status != 0))} failed, {fallback} to the general "
            f"solver{f' ({reasons})' if fallback else ''}) against the case-by-case path "
            f"{per * 1e3:.2f} ms CPU a case ({rows.size} cases: {per * n:.0f} s for {n}): "
            f"{per * n / cpu:.0f}x; the {int(both.sum())} cases both settle agree to "
            f"{err:.1e} of the fairlead tension"
        )
    return wp


if __name__ == "__main__":
    got = run(quick="--quick" in sys.argv)
    print("\n".join(got.summary_rows()))
    print("\n".join(got.notes))
