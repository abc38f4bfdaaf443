"""Work precision of the static solvers on drag-loaded 3D lines.

Cases (those of tests/validation/test_static_cross_check.py):

* ``fig8``: the dodaran-park Fig. 8 submersible cable (configs/dodaran-fig8-submersible-3d.yaml,
  L = 300 m, 0.5 N/m in water, ends (0, 0, -50) and (200, 0, -150) m) in a 0.1 m/s current
  at 60 deg to its plane: the current bends it out of its plane;
* ``towed``: a drag-dominated towed tether (L = 200 m, 3 N/m, 1 m/s current, a body force
  (-50, 20, -400) N at end B): drag about 15 times the weight.

Methods: the semi-analytic ``catenary`` solver (drag lumped at the nodes of N drag
elements, error O(h^2)) at N = 25 .. 1600, and the ``shooting`` solver (adaptive DOP853 on
the continuous ODE) at rtol 1e-6 .. 1e-12. Time: the solve itself
(``STATIC_SOLVERS[...].solve(problem)`` on a prepared StaticProblem), median over repeats.
Reference: shooting at rtol 1e-13, cross-checked against the catenary solver
Richardson-extrapolated from N = 800 and 1600, (4 X_1600 - X_800) / 3 (the difference is
noted). Error: the largest of the end-force and tension errors relative to the largest end
tension and the profile error relative to the line length.

Peer: MoorPy (optional extra ``peers``) models current on a line as a distributed load
computed on the straight chord and solves a catenary in the plane of weight plus that
load (its documented ``currentMod = 1``); it is run on the ``fig8`` case with fixed ends
and its error reported against the same reference.
"""

from __future__ import annotations

import copy

import numpy as np
import yaml

from cablestudy.bench import WorkPrecision, median_time
from cablestudy.statics import STATIC_SOLVERS, StaticProblem, StaticResult
from cablestudy.statics.shooting import ShootingSolver
from cablestudy.study.grid import expand_cases
from cablestudy.study.loader import parse_study_text
from cablestudy.study.problem import static_problem

FIG8 = {
    "name": "bench-fig8",
    "environment": {"fluid": "water", "current": [{"z": 0.0, "speed": 0.1, "heading_deg": 60.0}]},
    "line": {
        "segments": [
            {
                "length": 300.0,
                "diameter": 0.032,
                "weight_in_fluid": 0.5,
                "axial_stiffness": 1.608e8,
                "drag_normal": 1.2,
                "drag_tangential": 0.01,
            }
        ]
    },
    "ends": {
        "a": {"kind": "fixed", "position": [0.0, 0.0, -50.0]},
        "b": {"kind": "fixed", "position": [200.0, 0.0, -150.0]},
    },
    "analysis": {"static": {"nodes": 61, "tolerance": 1e-12}},
}


def towed() -> dict:
    d = copy.deepcopy(FIG8)
    d["name"] = "bench-towed"
    d["environment"]["current"] = [{"z": 0.0, "speed": 1.0, "heading_deg": 180.0}]
    d["line"]["segments"][0].update(length=200.0, weight_in_fluid=3.0)
    d["ends"] = {
        "a": {"kind": "fixed", "position": [0.0, 0.0, 0.0]},
        "b": {"kind": "force", "force": [-50.0, 20.0, -400.0]},
    }
    return d


def problem(data: dict, method: str, **settings: object) -> StaticProblem:
    d = copy.deepcopy(data)
    d["analysis"]["static"].update(method=method, **settings)
    _, cases = expand_cases(parse_study_text(yaml.safe_dump(d), "<bench>"))
    return static_problem(cases[0].study)


def difference(a: dict[str, np.ndarray], b: StaticResult) -> float:
    """Largest relative difference: end forces and tension per the largest end tension,
    profile per the line length."""
    scale = max(np.linalg.norm(b.force_a), np.linalg.norm(b.force_b))
    forces = max(np.abs(a["force_a"] - b.force_a).max(), np.abs(a["force_b"] - b.force_b).max())
    shape = np.abs(a["position"] - b.position).max() / float(b.s[-1])
    tension = np.abs(a["tension"] - b.tension).max() / scale
    return float(max(forces / scale, shape, tension))


def fields(r: StaticResult) -> dict[str, np.ndarray]:
    assert r.status == 0, r.message
    return {
        "force_a": r.force_a,
        "force_b": r.force_b,
        "position": r.position,
        "tension": r.tension,
    }


def one_case(label: str, title: str, data: dict, quick: bool) -> WorkPrecision:
    repeats = 3 if quick else 5
    wp = WorkPrecision(
        name=f"static_drag_{label}",
        title=title,
        error_name="max error: end forces & tension / T_end, profile / L [-]",
    )
    ref = ShootingSolver(rtol=1e-13).solve(problem(data, "shooting"))
    assert ref.status == 0, ref.message
    cat = STATIC_SOLVERS["catenary"]
    x800 = fields(cat.solve(problem(data, "catenary", drag_elements=800)))
    x1600 = fields(cat.solve(problem(data, "catenary", drag_elements=1600)))
    extrap = {k: (4.0 * x1600[k] - x800[k]) / 3.0 for k in x1600}
    wp.notes.append(
        f"reference shooting rtol 1e-13 vs catenary Richardson-extrapolated "
        f"from N = 800, 1600: difference {difference(extrap, ref):.1e}"
    )
    c = wp.curve("cablestudy catenary (semi-analytic)")
    for n in (25, 100, 400) if quick else (25, 50, 100, 200, 400, 800, 1600):
        prob = problem(data, "catenary", drag_elements=n)
        r = cat.solve(prob)
        c.add(
            f"drag_elements={n}",
            median_time(lambda prob=prob: cat.solve(prob), repeats=repeats, min_time=0.02),
            difference(fields(r), ref),
        )
    c = wp.curve("cablestudy shooting (ODE, DOP853)")
    prob = problem(data, "shooting")
    for rtol in (1e-6, 1e-9, 1e-12) if quick else (1e-6, 1e-8, 1e-10, 1e-11, 1e-12):
        solver = ShootingSolver(rtol=rtol)
        r = solver.solve(prob)
        c.add(
            f"rtol={rtol:g}",
            median_time(lambda solver=solver: solver.solve(prob), repeats=repeats, min_time=0.02),
            difference(fields(r), ref),
        )
    if label == "fig8":
        moorpy_fig8(wp, ref, repeats)
    return wp


def moorpy_fig8(wp: WorkPrecision, ref: StaticResult, repeats: int) -> None:
    """MoorPy's line in current on the fig8 case (end forces only; its profile is not on
    our arc-length nodes). MoorPy computes the current load from the previous profile,
    so a converged answer takes repeated solves (a fixed-point iteration): the setting is
    the number of passes, each ``Line.staticSolve(tol=1e-10)``."""
    try:
        import moorpy
    except ImportError:
        wp.notes.append("MoorPy not installed (pip install '.[peers]'): peer skipped")
        return
    import contextlib
    import io

    seg = FIG8["line"]["segments"][0]
    heading = np.radians(60.0)
    rho, g, d = 1025.0, 9.80665, seg["diameter"]
    mass = seg["weight_in_fluid"] / g + rho * np.pi * d**2 / 4  # MoorPy: w = (m - rho A) g
    curve = wp.curve("MoorPy (current as a chord load)", peer=True)
    scale = max(np.linalg.norm(ref.force_a), np.linalg.norm(ref.force_b))
    try:
        with contextlib.redirect_stdout(io.StringIO()):
            ms = moorpy.System(depth=1000.0, rho=rho, g=g)
            ms.currentMod = 1
            ms.current = np.array([0.1 * np.cos(heading), 0.1 * np.sin(heading), 0.0])
            ms.setLineType(
                dnommm=d * 1000,
                name="c",
                mass=mass,
                d_vol=d,
                EA=seg["axial_stiffness"],
                Cd=seg["drag_normal"],
                CdAx=seg["drag_tangential"],
            )
            ms.addPoint(1, [0.0, 0.0, -50.0])
            ms.addPoint(1, [200.0, 0.0, -150.0])
            ms.addLine(seg["length"], "c", nSegs=60)
            ms.pointList[0].attachLine(1, 0)
            ms.pointList[1].attachLine(1, 1)
            ms.initialize()
            line = ms.lineList[0]
            for passes in (1, 2, 4, 8, 16):

                def solve(passes: int = passes) -> None:
                    line.fCurrent = np.zeros(3)
                    for _ in range(passes):
                        line.staticSolve(tol=1e-10)

                solve()
                # fA, fB: forces of the line on its end points, as our force_a, force_b
                fa, fb = np.asarray(line.fA), np.asarray(line.fB)
                err = max(np.abs(fa - ref.force_a).max(), np.abs(fb - ref.force_b).max())
                curve.add(
                    f"passes={passes}",
                    median_time(solve, repeats=repeats, min_time=0.02),
                    float(err / scale),
                )
    except Exception as exc:  # noqa: BLE001 - a peer failure is reported, not fatal
        wp.notes.append(f"MoorPy failed on fig8: {type(exc).__name__}: {exc}")
        return
    wp.notes.append(
        f"MoorPy's error floor {min(curve.errors):.1e} is its model of current "
        "(load from the chord-wise profile, one catenary plane), not a tolerance"
    )


def run(quick: bool = False) -> list[WorkPrecision]:
    return [
        one_case(
            "fig8",
            "Drag-loaded 3D static line (dodaran Fig. 8, current 0.1 m/s at 60 deg)",
            FIG8,
            quick,
        ),
        one_case("towed", "Drag-dominated towed tether (1 m/s, drag ~15x weight)", towed(), quick),
    ]
