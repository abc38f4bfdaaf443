"""Static solvers on extreme but valid inputs: every case converges, or fails with a
nonzero status and a message; a converged case is finite and in equilibrium.

Equilibrium check: in still fluid the supports carry the whole weight, so
force_a + force_b = (0, 0, -w L) exactly; the solvers close the end position to
their tolerance (1e-9 relative by default), and the forces follow from the same
unknowns, so 1e-7 relative to the largest end force leaves two orders of margin for
Newton's last step and round-off in the sums (derivation: the Jacobian maps a
position residual r to a force error ~ r * stiffness; stiffness * 1e-9 L / T stays
below 1e-7 for the strains here, which are at most 50 %).
"""

from __future__ import annotations

import numpy as np
import pytest

from cablestudy.statics import STATIC_SOLVERS
from cablestudy.study.problem import static_problem

from .conftest import assert_honest, evaluate, study_dict

G = 9.80665

# (id, overrides) of extreme geometries and materials, all physically valid
EXTREMES = [
    ("near-taut", {"b": (99.99, 0.0, 0.0)}),
    ("stretched-1e-3", {"b": (100.1, 0.0, 0.0)}),
    ("stretched-soft-50pct", {"b": (150.0, 0.0, 0.0), "ea": 1e3}),
    ("very-slack", {"b": (1.0, 0.0, 0.0)}),
    ("vertical-folded", {"b": (0.0, 0.0, -50.0)}),
    ("vertical-hanging-taut", {"b": (0.0, 0.0, -100.05)}),
    ("near-vertical", {"b": (1e-4, 0.0, -99.0)}),
    ("u-shape-level", {"b": (30.0, 0.0, 0.0)}),
    ("buoyant", {"weight": -15.0, "mass": None}),
    ("neutral-stretched", {"weight": 0.0, "mass": None, "b": (100.5, 0.0, 0.0)}),
    ("ea-1e3", {"ea": 1e3}),
    ("ea-1e12", {"ea": 1e12}),
    ("ten-km", {"length": 10_000.0, "b": (9_000.0, 0.0, -2_000.0)}),
    ("one-metre", {"length": 1.0, "b": (0.8, 0.0, -0.2)}),
    ("3d-inclined", {"b": (40.0, -50.0, 30.0)}),
]


def _solvers_for(data: dict) -> list[str]:
    import yaml

    from cablestudy.study.grid import expand_cases
    from cablestudy.study.loader import parse_study_text

    _, cases = expand_cases(parse_study_text(yaml.safe_dump(data), "<x>"))
    problem = static_problem(cases[0].study)
    return [m for m, s in sorted(STATIC_SOLVERS.items()) if not s.unsupported(problem)]


CASES = [
    pytest.param(name, overrides, method, id=f"{name}-{method}")
    for name, overrides in EXTREMES
    for method in _solvers_for(study_dict(**overrides))
]


#: (geometry, method) pairs where a method may honestly fail, and why. The default
#: method ('catenary') and the exact one must converge everywhere.
SINGULAR_FOR = {
    ("vertical-folded", "shooting"): "a zero-span fold has zero tension at the fold point, "
    "where the angle form of the equilibrium ODE is singular (with 1 mm of span it converges)",
}


@pytest.mark.parametrize(("name", "overrides", "method"), CASES)
def test_extreme_static_case(name: str, overrides: dict, method: str) -> None:
    data = study_dict(method=method, **overrides)
    rec = evaluate(data)
    assert_honest(rec)
    if (name, method) in SINGULAR_FOR and rec.status != 0:
        return  # an honest failure with a message (assert_honest) is the right answer
    assert rec.status == 0, f"{name}/{method}: {rec.message}"
    seg = data["line"]["segments"][0]
    rho = 1025.0
    area = np.pi * seg["diameter"] ** 2 / 4
    w = seg.get("weight_in_fluid", (seg.get("mass_per_length", 0.0) - rho * area) * G)
    total = rec.data["force_a"] + rec.data["force_b"]
    scale = max(np.abs(rec.data["force_a"]).max(), np.abs(rec.data["force_b"]).max(), abs(w))
    expected = np.array([0.0, 0.0, -w * seg["length"]])
    atol = 1e-7 * scale
    if method == "discrete":
        # the lumped model balances each node to its Newton residual: the supports carry
        # the weight up to the residuals summed over the nodes (a stiff line's residual
        # floor is EA times the rounding of the node coordinates over an element)
        atol = max(atol, float(rec.data["static_residual"]) * len(rec.data["x"]))
    np.testing.assert_allclose(total, expected, atol=atol)
    end = np.array([rec.data["x"][-1], rec.data["y"][-1], rec.data["z"][-1]])
    np.testing.assert_allclose(
        end, data["ends"]["b"]["position"], atol=1e-8 * max(seg["length"], 1.0)
    )


def test_weightless_slack_line_is_rejected_before_work() -> None:
    """A weightless line whose chord is shorter than its length has no unique shape:
    the honest answer is a config error naming the field, not an arbitrary shape."""
    from cablestudy.study.loader import StudyError

    with pytest.raises(StudyError, match=r"ends\.b\.position.*undetermined"):
        evaluate(study_dict(weight=0.0, mass=None, b=(50.0, 0.0, 0.0)))


# current extremes: drag far above the weight, and a current that reverses with depth
CURRENT_EXTREMES = [
    (
        "drag-250x-weight",
        {
            "weight": 0.5,
            "mass": None,
            "diameter": 0.05,
            "b": (60.0, 0.0, -40.0),
            "current": [{"z": 0.0, "speed": 2.0, "heading_deg": 90.0}],
        },
    ),
    (
        "current-reversing-with-depth",
        {
            "b": (60.0, 20.0, -60.0),
            "current": [
                {"z": -100.0, "speed": 1.0, "heading_deg": 180.0},
                {"z": 0.0, "speed": 1.0, "heading_deg": 0.0},
            ],
        },
    ),
]


@pytest.mark.parametrize(
    ("name", "overrides"), CURRENT_EXTREMES, ids=[c[0] for c in CURRENT_EXTREMES]
)
def test_current_extremes_both_solvers_agree(name: str, overrides: dict) -> None:
    """Both drag-capable solvers converge, and agree: the semi-analytic solver's
    lumping error is O(h^2); at 400 drag elements it was 2.8e-5 of the end tension
    on the towed tether with drag 15 times its weight
    (tests/validation/test_static_cross_check.py), so 1e-3 leaves a factor 30 for drag
    250 times the weight (0.5 N/m against 123 N/m of normal drag); shooting's own error
    is below 1e-9."""
    recs = {}
    for method in ("catenary", "shooting"):
        data = study_dict(method=method, **overrides)
        if method == "catenary":
            data["analysis"]["static"]["drag_elements"] = 400
        rec = evaluate(data)
        assert_honest(rec)
        assert rec.status == 0, f"{name}/{method}: {rec.message}"
        recs[method] = rec
    a, b = recs["catenary"].data, recs["shooting"].data
    scale = max(np.abs(b["force_a"]).max(), np.abs(b["force_b"]).max())
    for key in ("force_a", "force_b"):
        np.testing.assert_allclose(a[key], b[key], atol=1e-3 * scale)
    # and the drag dominates indeed: the end forces are far from the still-water balance
    total = b["force_a"] + b["force_b"]
    assert np.hypot(total[0], total[1]) > 0.1 * scale
