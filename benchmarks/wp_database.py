"""Work precision of the quasi-static database (issue 12 item 7): a lookup against a
direct static solve, at random end-B positions inside the grid.

Line: a suspended two-section line in water (chain 60 m of 80 kg/m over wire 140 m of
12 kg/m, EA 8e8 / 2e8 N), end A fixed, end B over horizontal distance 120..180 m and
height difference 60..120 m (no seabed: the tabulated quantities are smooth, so the
bicubic error falls as h^4; with touchdown the laid length has a kink where the line
lifts off, which any smooth interpolant rounds). Reference: the `catenary` solver at
tolerance 1e-12 at 200 random points (seeded). Error: the largest end-force component
error over the points, relative to the largest end tension. Times: the median lookup
(all quantities at once) and the median direct solve (compiled catenary, the fastest
static path) at tolerance 1e-9 and 1e-12.
"""

from __future__ import annotations

import numpy as np

from cablestudy.bench import WorkPrecision, median_time

R0, R1, H0, H1 = 110.0, 150.0, 50.0, 100.0


def study(n: int, tolerance: float = 1e-12):  # noqa: ANN201
    from cablestudy.config import Study

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
                "database": {
                    "horizontal_distance": {"start": R0, "stop": R1, "num": n},
                    "height_difference": {"start": H0, "stop": H1, "num": n},
                },
            },
        }
    )


def direct(st, r: float, h: float):  # noqa: ANN001, ANN201
    from dataclasses import replace

    from cablestudy.problem import static_problem
    from cablestudy.statics import EndCondition

    p = static_problem(st)
    rB = np.asarray(p.end_a.position) + np.array([r, 0.0, h])
    return replace(p, end_b=EndCondition(kind="fixed", position=rB))


def run(quick: bool = False) -> WorkPrecision:
    from cablestudy.database import QUANTITIES, QuasiStaticDatabase, solve_database
    from cablestudy.statics import STATIC_SOLVERS

    solver = STATIC_SOLVERS["catenary"]
    rng = np.random.default_rng(12)
    npts = 60 if quick else 200
    pts = np.column_stack((rng.uniform(R0, R1, npts), rng.uniform(H0, H1, npts)))
    ref_study = study(4)
    refs = []
    for r, h in pts:
        res = solver.solve(direct(ref_study, r, h))
        assert res.status == 0, res.message
        refs.append(np.concatenate((res.force_a, res.force_b)))
    refs = np.array(refs)
    scale = float(np.max(np.linalg.norm(refs[:, 3:], axis=1)))
    wp = WorkPrecision(
        name="database_lookup",
        title="Quasi-static database: lookup vs direct solve",
        error_name="max end-force error / max end tension at 200 random points [-]",
        time_name="median wall time per evaluation [s]",
    )
    c = wp.curve("cablestudy database lookup (bicubic C1)")
    for n in (5, 9, 17) if quick else (5, 9, 17, 33):
        st = study(n)
        data = solve_database(st)
        db = QuasiStaticDatabase.from_arrays(
            data["database_distance_grid"],
            data["database_height_grid"],
            {k: data[f"database_{k}"] for k in QUANTITIES},
        )
        got = np.array(
            [
                np.concatenate((o["force_a"], o["force_b"]))
                for o in (db.lookup(r, h) for r, h in pts)
            ]
        )
        err = float(np.max(np.abs(got - refs))) / scale
        t = median_time(lambda db=db: db.lookup_array(130.3, 70.7), repeats=5)
        t_dict = median_time(lambda db=db: db.lookup(130.3, 70.7), repeats=5)
        wp.notes.append(f"{n}x{n}: lookup as a dict of named quantities {t_dict * 1e6:.1f} us")
        c.add(f"{n}x{n} grid", t, err)
    c = wp.curve("cablestudy catenary direct solve (compiled)")
    for tol in (1e-6, 1e-9, 1e-12):
        st = study(4, tol)
        probs = [direct(st, r, h) for r, h in pts[:40]]
        got = np.array(
            [np.concatenate((x.force_a, x.force_b)) for x in (solver.solve(p) for p in probs)]
        )
        err = float(np.max(np.abs(got - refs[:40]))) / scale
        p0 = probs[0]
        c.add(f"tolerance={tol:g}", median_time(lambda p0=p0: solver.solve(p0), repeats=5), err)
    return wp


if __name__ == "__main__":
    w = run()
    for cv in w.curves:
        for s, t, e in zip(cv.settings, cv.times, cv.errors, strict=True):
            print(f"{cv.method:45s} {s:18s} {t * 1e6:10.1f} us  error {e:.2e}")
