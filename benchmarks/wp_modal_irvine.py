"""Work precision of the modal analysis against Irvine's linear theory.

A level cable in vacuum (configs/irvine-modal-lambda.yaml: span l = 100 m, m = 1 kg/m,
sag/span 1/40, so H = w l / (8 / 40) = 4903 N), with EA chosen for Irvine's cable
parameter lambda^2 ~ 100 (past the first crossover 4 pi^2, where the first symmetric
in-plane mode has risen above the first antisymmetric one). Error: the largest relative
error of the 4 lowest natural frequencies (out-of-plane, antisymmetric and symmetric
in-plane together), (a) against Irvine's theory (cablestudy.dynamics.irvine, lambda^2
and H taken from our exact static solution), which itself neglects terms of order
(sag/span)^2 ~ 1e-3, so that curve flattens at the theory's own error; (b) against our
own mesh limit, the Richardson extrapolation (4 f_2N - f_N) / 3 of the two finest uniform
meshes, which shows the O(h^2) convergence of the lumped-mass model. Methods: the
'uniform' and 'graded' (equal transverse travel time) meshes at 10 .. 640 elements.
Time: ``solve_modal`` (mesh, eigenproblem) with the static solution prepared, median
over repeats.
"""

from __future__ import annotations

import copy
import math

import numpy as np
import yaml

from cablestudy.bench import WorkPrecision, median_time

EA, L0 = 12319769.88, 100.1266998  # a pair of configs/irvine-modal-lambda.yaml
BASE = {
    "name": "bench-irvine",
    "environment": {"fluid": "vacuum", "gravity": 9.80665},
    "line": {
        "segments": [
            {"length": L0, "diameter": 0.01, "mass_per_length": 1.0, "axial_stiffness": EA}
        ]
    },
    "ends": {
        "a": {"kind": "fixed", "position": [0.0, 0.0, 0.0]},
        "b": {"kind": "fixed", "position": [100.0, 0.0, 0.0]},
    },
    "analysis": {
        "static": {"method": "analytic", "nodes": 101, "tolerance": 1e-12},
        "modal": {"modes": 6, "mode_shapes": False},
    },
}
MODES = 4


def case(elements: int, mesh: str):  # noqa: ANN201
    from cablestudy.study.grid import expand_cases
    from cablestudy.study.loader import parse_study_text

    d = copy.deepcopy(BASE)
    d["analysis"]["modal"].update(elements=elements, mesh=mesh)
    _, cases = expand_cases(parse_study_text(yaml.safe_dump(d), "<bench>"))
    return cases[0]


def run(quick: bool = False) -> list[WorkPrecision]:
    from cablestudy.analyses.modal import solve_modal
    from cablestudy.analyses.static import solve_static
    from cablestudy.dynamics.irvine import cable_parameter, frequencies

    c0 = case(100, "uniform")
    static = solve_static(c0, None)
    H = abs(float(static.force_a[0]))
    sag = -float(np.min(static.position[:, 2]))
    w, span = 9.80665, 100.0
    # L_e = int (ds/dx)^3 dx on the static shape
    x, z = static.position[:, 0], static.position[:, 2]
    slope = np.gradient(z, x)
    le = float(np.trapezoid((1.0 + slope**2) ** 1.5, x))
    lam2 = cable_parameter(
        span=span, weight=w, horizontal_tension=H, axial_stiffness=EA, effective_length=le
    )
    # the MODES lowest of Irvine's three families together [Hz] (mass 1 kg/m)
    bar = np.sort(np.concatenate(list(frequencies(lam2, MODES).values())))[:MODES]
    irvine = bar * math.sqrt(H / 1.0) / span / (2.0 * math.pi)

    repeats = 3 if quick else 5
    meshes = (10, 40, 160) if quick else (10, 20, 40, 80, 160, 320, 640)
    fine = []
    for n in (1280, 2560):
        c = case(n, "uniform")
        fine.append(solve_modal(c, solve_static(c, None), None).frequency[:MODES])
    limit = (4.0 * fine[1] - fine[0]) / 3.0

    vs_theory = WorkPrecision(
        name="modal_irvine",
        title=f"Modal: 4 lowest frequencies vs Irvine (lambda^2 = {lam2:.0f}, sag/span 1/40)",
        error_name="max relative frequency error vs Irvine [-]",
    )
    vs_mesh = WorkPrecision(
        name="modal_mesh",
        title="Modal: 4 lowest frequencies vs the mesh limit (Richardson)",
        error_name="max relative frequency error vs mesh limit [-]",
    )
    for mesh in ("uniform", "graded"):
        a = vs_theory.curve(f"cablestudy {mesh} mesh")
        b = vs_mesh.curve(f"cablestudy {mesh} mesh")
        for n in meshes:
            c = case(n, mesh)
            st = solve_static(c, None)
            res = solve_modal(c, st, None)
            assert res.success, res.message
            t = median_time(
                lambda c=c, st=st: solve_modal(c, st, None), repeats=repeats, min_time=0.02
            )
            f = res.frequency[:MODES]
            a.add(f"elements={n}", t, float(np.max(np.abs(f / irvine - 1.0))))
            b.add(f"elements={n}", t, float(np.max(np.abs(f / limit - 1.0))))
    theory = float(np.max(np.abs(limit / irvine - 1.0)))
    vs_theory.notes.append(
        f"lambda^2 = {lam2:.2f}, sag/span = {sag / span:.4f}; Irvine's 4 lowest: "
        + ", ".join(f"{v:.5f}" for v in irvine)
        + " Hz; our mesh limit: "
        + ", ".join(f"{v:.5f}" for v in limit)
        + f" Hz: they differ by {theory:.1e}, the order of the (sag/span)^2 terms "
        "Irvine's theory drops"
    )
    vs_mesh.notes.append(
        "reference: (4 f_2560 - f_1280) / 3 on uniform meshes; the tension "
        "of this shallow cable is nearly uniform, so the graded mesh is "
        "nearly the uniform one"
    )
    return [vs_theory, vs_mesh]
