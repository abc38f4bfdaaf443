"""Work precision of the non-linear axial laws in the `catenary` solver (issue 12: a
non-linear-law catenary at most 5x the cost of the linear one at the same tolerance).

Line: two segments in water (60 m of 30 kg/m, 60 m of 8 kg/m) between A (0, 0, -60) and
B (95, 0, -5), with the same law on both: linear EA 4e7 N (the reference cost), the
issue's polynomial shape scaled to it (4e7 e + 2e8 e^2 + 5e8 e^3), a steel wire (k 4e7
N, d 0.002) and a PCHIP table. Each law's reference: its own solve at tolerance 1e-13
with a fine quadrature (32 nodes per sub-interval, 10 grades). Error: largest end-force
component error over the end tension. Times: median solve at tolerance 1e-6, 1e-9,
1e-12 on a prepared problem; the linear law through the compiled batch kernel (its
default) and through the general path (the one the non-linear laws take).
"""

from __future__ import annotations

import numpy as np

from cablestudy.bench import WorkPrecision, median_time

LAWS = {
    "linear EA": {"axial_stiffness": 4.0e7},
    "polynomial": {"axial": {"law": "polynomial", "coefficients": [4.0e7, 2.0e8, 5.0e8]}},
    "steel wire": {"axial": {"law": "steel_wire", "stiffness": 4.0e7, "offset": 0.002}},
    "table": {
        "axial": {
            "law": "table",
            "strain": [0.0, 0.001, 0.002, 0.01],
            "tension": [0.0, 3.0e4, 7.0e4, 4.5e5],
        }
    },
}


def problem(axial: dict, tolerance: float):  # noqa: ANN201
    from cablestudy.study import Study
    from cablestudy.study.problem import static_problem

    seg = {"length": 60.0, "diameter": 0.08, "mass_per_length": 30.0, **axial}
    return static_problem(
        Study.model_validate(
            {
                "name": "w",
                "environment": {"fluid": "water"},
                "line": {"segments": [seg, {**seg, "diameter": 0.05, "mass_per_length": 8.0}]},
                "ends": {
                    "a": {"kind": "fixed", "position": [0.0, 0.0, -60.0]},
                    "b": {"kind": "fixed", "position": [95.0, 0.0, -5.0]},
                },
                "analysis": {
                    "static": {"method": "catenary", "nodes": 101, "tolerance": tolerance}
                },
            }
        )
    )


def run(quick: bool = False) -> WorkPrecision:
    from cablestudy.statics import STATIC_SOLVERS, law_pieces

    solver = STATIC_SOLVERS["catenary"]
    repeats = 3 if quick else 7
    wp = WorkPrecision(
        name="axial_laws",
        title="Non-linear axial laws in the catenary solver: cost against the linear law",
        error_name="max end-force error / end tension [-]",
    )
    for name, axial in LAWS.items():
        old = law_pieces.QUADRATURE_POINTS, law_pieces.QUADRATURE_GRADES
        law_pieces.QUADRATURE_POINTS, law_pieces.QUADRATURE_GRADES = 32, 10
        try:
            ref = solver.solve(problem(axial, 1e-13), compiled=False)
        finally:
            law_pieces.QUADRATURE_POINTS, law_pieces.QUADRATURE_GRADES = old
        scale = float(np.linalg.norm(ref.force_b))
        variants = (
            [("", True)] if name != "linear EA" else [(" (compiled)", True), (" (general)", False)]
        )
        for label, compiled in variants:
            c = wp.curve(f"catenary, {name}{label}")
            for tol in (1e-6, 1e-9, 1e-12):
                p = problem(axial, tol)
                r = solver.solve(p, compiled=compiled)
                assert r.status == 0, r.message
                err = (
                    max(
                        float(np.max(np.abs(r.force_a - ref.force_a))),
                        float(np.max(np.abs(r.force_b - ref.force_b))),
                    )
                    / scale
                )
                t = median_time(
                    lambda p=p, c_=compiled: solver.solve(p, compiled=c_), repeats=repeats
                )
                c.add(f"tolerance={tol:g}", t, err)
    lin = {c.method: c for c in wp.curves}
    base_c, base_g = lin["catenary, linear EA (compiled)"], lin["catenary, linear EA (general)"]
    for c in wp.curves:
        if "linear" in c.method:
            continue
        ratios = ", ".join(
            f"{s}: {t / tc:.1f}x compiled linear, {t / tg:.1f}x general linear"
            for s, t, tc, tg in zip(c.settings, c.times, base_c.times, base_g.times, strict=True)
        )
        wp.notes.append(f"{c.method}: {ratios}")
    return wp


if __name__ == "__main__":
    w = run()
    for cv in w.curves:
        for s, t, e in zip(cv.settings, cv.times, cv.errors, strict=True):
            print(f"{cv.method:40s} {s:18s} {t * 1e3:8.2f} ms  error {e:.2e}")
    print("\n".join(w.notes))
