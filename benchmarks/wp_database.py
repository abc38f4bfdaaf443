"""Work precision of the quasi-static database (issue 12 item 7): a lookup against a
direct static solve, at random end-B positions inside the grid, for both grids.

Line: a suspended two-section line in water (chain 60 m of 80 kg/m over wire 140 m of
12 kg/m, EA 8e8 / 2e8 N), end A fixed, no seabed (the tabulated quantities are smooth,
so the bicubic error falls as h^4; with touchdown the laid length has a kink where the
line lifts off, which any smooth interpolant rounds). End B over
- grid cartesian: horizontal distance 110..150 m, height difference 50..100 m;
- grid radial (the seed's grid for lines off the seabed): distance 100..150 m, chord
  angle -30..30 deg (B from 75 m below A to 75 m above it).
Reference: the `catenary` solver at tolerance 1e-12 at 200 random points (seeded,
uniform in the grid's own coordinates). Error: the largest end-force component error
over the points, relative to the largest end tension. Times: the median lookup by
(x, z) (all quantities at once; the radial one converts to (d, a) first) and the
median direct solve (compiled catenary, the fastest static path) at tolerance 1e-6,
1e-9 and 1e-12.
"""

from __future__ import annotations

import numpy as np

from cablestudy.bench import WorkPrecision, median_time

R0, R1, H0, H1 = 110.0, 150.0, 50.0, 100.0
D0, D1, A0, A1 = 100.0, 150.0, -30.0, 30.0


def study(n: int, tolerance: float = 1e-12, grid: str = "cartesian"):  # noqa: ANN201
    if grid == "radial":
        database = {
            "grid": "radial",
            "distance": {"start": D0, "stop": D1, "num": n},
            "angle_deg": {"start": A0, "stop": A1, "num": n},
        }
    else:
        database = {
            "horizontal_distance": {"start": R0, "stop": R1, "num": n},
            "height_difference": {"start": H0, "stop": H1, "num": n},
        }
    from cablestudy.study import Study

    return Study.model_validate(
        {
            "name": "db",
            "environment": {"fluid": "water"},
            "line": {
                "segments": [
                    {
                        "length": 60.0,
                        "diameter": 0.09,
                        "mass_per_length": 80.0,
                        "axial_stiffness": 8e8,
                    },
                    {
                        "length": 140.0,
                        "diameter": 0.06,
                        "mass_per_length": 12.0,
                        "axial_stiffness": 2e8,
                    },
                ]
            },
            "ends": {
                "a": {"kind": "fixed", "position": [0.0, 0.0, -150.0]},
                "b": {"kind": "fixed", "position": [150.0, 0.0, -60.0]},
            },
            "analysis": {
                "static": {"method": "catenary", "nodes": 41, "tolerance": tolerance},
                "database": database,
            },
        }
    )


def direct(st, r: float, h: float):  # noqa: ANN001, ANN201
    from dataclasses import replace

    from cablestudy.statics import EndCondition
    from cablestudy.study.problem import static_problem

    p = static_problem(st)
    rB = np.asarray(p.end_a.position) + np.array([r, 0.0, h])
    return replace(p, end_b=EndCondition(kind="fixed", position=rB))


def points(grid: str, n: int, rng: np.random.Generator) -> np.ndarray:
    """``n`` random end-B positions (x, z) from end A inside the grid, uniform in its
    own coordinates."""
    if grid == "radial":
        d = rng.uniform(D0, D1, n)
        a = np.radians(rng.uniform(A0, A1, n))
        return np.column_stack((d * np.cos(a), d * np.sin(a)))
    return np.column_stack((rng.uniform(R0, R1, n), rng.uniform(H0, H1, n)))


def work_precision(grid: str, quick: bool) -> WorkPrecision:
    from cablestudy.analyses.database import (
        QUANTITIES,
        QuasiStaticDatabase,
        grid_values,
        solve_database,
    )
    from cablestudy.analyses.variables import DATABASE_LAYOUTS
    from cablestudy.statics import STATIC_SOLVERS

    solver = STATIC_SOLVERS["catenary"]
    prefix = DATABASE_LAYOUTS[grid].prefix
    rng = np.random.default_rng(12)
    npts = 60 if quick else 200
    pts = points(grid, npts, rng)
    probe = tuple(pts[0])
    ref_study = study(4, grid=grid)
    refs = []
    for r, h in pts:
        res = solver.solve(direct(ref_study, r, h))
        assert res.status == 0, res.message
        refs.append(np.concatenate((res.force_a, res.force_b)))
    refs = np.array(refs)
    scale = float(np.max(np.linalg.norm(refs[:, 3:], axis=1)))
    suffix = "" if grid == "cartesian" else "_radial"
    wp = WorkPrecision(
        name=f"database_lookup{suffix}",
        title=f"Quasi-static database ({grid} grid): lookup vs direct solve",
        error_name=f"max end-force error / max end tension at {npts} random points [-]",
        time_name="median wall time per evaluation [s]",
    )
    c = wp.curve(f"cablestudy database lookup ({grid} grid, bicubic C1)")
    for n in (5, 9, 17) if quick else (5, 9, 17, 33):
        st = study(n, grid=grid)
        data = solve_database(st)
        P, Q = grid_values(st)
        db = QuasiStaticDatabase.from_arrays(
            P, Q, {k: data[f"{prefix}{k}"] for k in QUANTITIES}, grid=grid
        )
        got = np.array(
            [
                np.concatenate((o["force_a"], o["force_b"]))
                for o in (db.lookup(r, h) for r, h in pts)
            ]
        )
        err = float(np.max(np.abs(got - refs))) / scale
        t = median_time(lambda db=db: db.lookup_array(*probe), repeats=5)
        t_dict = median_time(lambda db=db: db.lookup(*probe), repeats=5)
        wp.notes.append(f"{n}x{n}: lookup as a dict of named quantities {t_dict * 1e6:.1f} us")
        c.add(f"{n}x{n} grid", t, err)
    c = wp.curve("cablestudy catenary direct solve (compiled)")
    for tol in (1e-6, 1e-9, 1e-12):
        st = study(4, tol, grid=grid)
        probs = [direct(st, r, h) for r, h in pts[:40]]
        got = np.array(
            [np.concatenate((x.force_a, x.force_b)) for x in (solver.solve(p) for p in probs)]
        )
        err = float(np.max(np.abs(got - refs[:40]))) / scale
        p0 = probs[0]
        c.add(f"tolerance={tol:g}", median_time(lambda p0=p0: solver.solve(p0), repeats=5), err)
    return wp


def run(quick: bool = False) -> list[WorkPrecision]:
    return [work_precision(grid, quick) for grid in ("cartesian", "radial")]


if __name__ == "__main__":
    for w in run():
        for cv in w.curves:
            for s, t, e in zip(cv.settings, cv.times, cv.errors, strict=True):
                print(f"{cv.method:50s} {s:18s} {t * 1e6:10.1f} us  error {e:.2e}")
