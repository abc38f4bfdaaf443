"""Work precision of the static catenary: the Fig. 4 steel catenary of the dodaran-park
seed (L = 100 m, 2.466 kg/m in air, EA = 6.283e7 N, B at (92.5, -8.6) m from A).

Reference: Irvine's two closure equations solved with mpmath at 40 significant digits
(independent of the float code). Error: largest end-force component error relative to
the end tension. Methods: the exact `analytic` solver (Irvine's equations by Newton),
the semi-analytic `catenary` solver and the `shooting` solver, each timed on the solve
itself (``STATIC_SOLVERS[...].solve(problem)`` on a prepared StaticProblem of 101
output nodes); the per-case overhead of the pipeline (config -> problem -> solve ->
record, ``evaluate_case`` with the static cache cleared) is timed separately and noted.
Peer: MoorPy's catenary (optional extra `peers`) at several Tol.
"""

from __future__ import annotations

import numpy as np

from cablestudy.bench import WorkPrecision, median_time
from cablestudy.bench import _fmt_time as _fmt

L, MASS, G, EA = 100.0, 2.466, 9.80665, 6.283e7
SPAN, RISE = 92.5, -8.6
W = MASS * G  # air buoyancy ignored in the reference and in every method alike


def reference() -> np.ndarray:
    """(H, V_A, V_B) from Irvine's equations at 40 digits."""
    import mpmath as mp

    mp.mp.dps = 40
    l, h, Lm, w, ea = (mp.mpf(v) for v in (SPAN, RISE, L, W, EA))

    def eqs(H, VA):  # noqa: ANN001, ANN202
        VB = VA + w * Lm
        x = H * Lm / ea + H / w * (mp.asinh(VB / H) - mp.asinh(VA / H))
        z = (VA * Lm + w * Lm**2 / 2) / ea + (mp.sqrt(H**2 + VB**2) - mp.sqrt(H**2 + VA**2)) / w
        return [x - l, z - h]

    H, VA = mp.findroot(eqs, (mp.mpf(1600), mp.mpf(-1300)))
    return np.array([float(H), float(VA), float(VA + w * Lm)])


def problem(tolerance: float = 1e-12):  # noqa: ANN201
    """The Fig. 4 case as a StaticProblem (in vacuum: weight m g, as in the reference)."""
    from cablestudy.statics import EndCondition, LineModel, Medium, StaticProblem

    def one(v: float) -> np.ndarray:
        return np.array([float(v)])

    line = LineModel(
        length=one(L),
        weight=one(W),
        mass=one(MASS),
        axial_stiffness=one(EA),
        diameter=one(0.02),
        drag_normal=one(1.2),
        drag_tangential=one(0.01),
        added_mass_normal=one(1.0),
        added_mass_tangential=one(0.0),
        bending_stiffness=one(0.0),
        damping_ratio=one(0.0),
        attachment_s=np.zeros(0),
        attachment_force=np.zeros((0, 3)),
        attachment_mass=np.zeros(0),
        attachment_volume=np.zeros(0),
    )
    return StaticProblem(
        line=line,
        medium=Medium(density=0.0, gravity=G),
        end_a=EndCondition(kind="fixed", position=np.zeros(3)),
        end_b=EndCondition(kind="fixed", position=np.array([SPAN, 0.0, RISE])),
        n_nodes=101,
        tolerance=tolerance,
    )


def pipeline_overhead(repeats: int) -> tuple[float, float]:
    """(median time of one case through evaluate_case, of its static solve alone) [s],
    method catenary at tolerance 1e-12, static cache cleared before every call."""
    import yaml

    from cablestudy.analyses.evaluate import evaluate_case
    from cablestudy.analyses.static import _STATIC_CACHE
    from cablestudy.statics import STATIC_SOLVERS
    from cablestudy.study.grid import expand_cases
    from cablestudy.study.loader import parse_study_text
    from cablestudy.study.problem import static_problem

    data = {
        "name": "bench",
        "environment": {"fluid": "vacuum", "gravity": G},
        "line": {
            "segments": [
                {"length": L, "diameter": 0.02, "mass_per_length": MASS, "axial_stiffness": EA}
            ]
        },
        "ends": {
            "a": {"kind": "fixed", "position": [0.0, 0.0, 0.0]},
            "b": {"kind": "fixed", "position": [SPAN, 0.0, RISE]},
        },
        "analysis": {"static": {"method": "catenary", "nodes": 101, "tolerance": 1e-12}},
    }
    _, cases = expand_cases(parse_study_text(yaml.safe_dump(data), "<bench>"))

    def whole() -> None:
        _STATIC_CACHE.clear()
        evaluate_case(cases[0])

    prob = static_problem(cases[0].study)
    solve = STATIC_SOLVERS["catenary"].solve
    return (median_time(whole, repeats=repeats), median_time(lambda: solve(prob), repeats=repeats))


def run(quick: bool = False) -> WorkPrecision:
    from cablestudy.statics import STATIC_SOLVERS
    from cablestudy.statics.elastic_catenary import solve_between
    from cablestudy.statics.shooting import ShootingSolver

    ref = reference()
    tension = float(np.hypot(ref[0], ref[1]))
    wp = WorkPrecision(
        name="static_catenary",
        title="Static catenary (dodaran Fig. 4): end-force error vs time",
        error_name="max end-force error / end tension [-]",
    )
    s = np.linspace(0.0, L, 101)
    repeats = 3 if quick else 7

    def err_of(fa: np.ndarray, fb: np.ndarray) -> float:
        got = np.array([np.hypot(fa[0], fa[1]), fa[2], -fb[2]])
        return float(np.max(np.abs(got - ref)) / tension)

    c = wp.curve("cablestudy analytic (Irvine, Newton)")
    for tol in (1e-4, 1e-8, 1e-12):
        r = solve_between((0, 0, 0), (SPAN, 0, RISE), L, W, EA, s, tolerance=tol)
        c.add(
            f"tol={tol:g}",
            median_time(
                lambda tol=tol: solve_between(
                    (0, 0, 0), (SPAN, 0, RISE), L, W, EA, s, tolerance=tol
                ),
                repeats=repeats,
            ),
            err_of(r.force_a, r.force_b),
        )

    c = wp.curve("cablestudy catenary (semi-analytic)")
    for tol in (1e-4, 1e-6, 1e-8, 1e-10, 1e-12):
        prob = problem(tol)
        r = STATIC_SOLVERS["catenary"].solve(prob)
        assert r.status == 0, r.message
        c.add(
            f"tolerance={tol:g}",
            median_time(lambda prob=prob: STATIC_SOLVERS["catenary"].solve(prob), repeats=repeats),
            err_of(r.force_a, r.force_b),
        )

    # many cases in one task (what the runner does with a chunk of still-water cases):
    # the compiled batch kernel, timed per case over a batch of the same problem
    from cablestudy.statics.batch import solve_batch

    c = wp.curve("cablestudy catenary, batch of 1000 cases per task")
    for tol in (1e-6, 1e-9, 1e-12):
        probs = [problem(tol)] * 1000
        solve_batch(probs[:4])  # numba compile (cached on disk) outside the timing
        r = solve_batch(probs)[0]
        assert r.status == 0, r.message
        batch_time = median_time(lambda probs=probs: solve_batch(probs), repeats=repeats)
        c.add(f"tolerance={tol:g}", batch_time / len(probs), err_of(r.force_a, r.force_b))

    c = wp.curve("cablestudy shooting (ODE, DOP853)")
    for rtol in (1e-6, 1e-9, 1e-12) if quick else (1e-6, 1e-8, 1e-10, 1e-12):
        solver, prob = ShootingSolver(rtol=rtol), problem(1e-12)
        r = solver.solve(prob)
        assert r.status == 0, r.message
        c.add(
            f"rtol={rtol:g}",
            median_time(lambda solver=solver, prob=prob: solver.solve(prob), repeats=repeats),
            err_of(r.force_a, r.force_b),
        )

    whole, solve = pipeline_overhead(repeats)
    over = (
        f"overhead {_fmt(whole - solve)} per case"
        if whole > solve
        else "overhead below the timing noise"
    )
    wp.notes.append(
        f"one case through the pipeline (evaluate_case: config -> problem -> catenary solve "
        f"-> record, 101 nodes) takes {_fmt(whole)}; the solve alone {_fmt(solve)}: {over}"
    )
    try:
        from moorpy.Catenary import catenary
    except ImportError:
        wp.notes.append("MoorPy not installed (pip install '.[peers]'): peer skipped")
        return wp
    p = wp.curve("MoorPy catenary", peer=True)
    for tol in (1e-4, 1e-6, 1e-9):
        fAH, fAV, fBH, fBV, _ = catenary(SPAN, RISE, L, EA, W, CB=-1e3, Tol=tol, MaxIter=200)
        # MoorPy returns (fAH, fAV, fBH, fBV) of the line's end forces, positive up:
        # in our tension-vector terms (H, V_A, V_B) = (fAH, fAV, -fBV)
        err = float(np.max(np.abs(np.array([fAH, fAV, -fBV]) - ref)) / tension)
        p.add(
            f"Tol={tol:g}",
            median_time(
                lambda tol=tol: catenary(SPAN, RISE, L, EA, W, CB=-1e3, Tol=tol, MaxIter=200),
                repeats=repeats,
            ),
            err,
        )
    return wp
