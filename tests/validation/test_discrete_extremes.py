"""Method ``discrete`` on the lines issue 21 found it wrong or unable on, and on sweeps of
EA, length and node count: converged and right (against method ``catenary``, the exact
elastic catenary), with the error falling as h^2.

Before the mixed (position and tension) Newton (measured on 5634c87, the branch point):
* 2 m wire (2.466 kg/m, EA 6.283e7) at 1001 nodes: end tensions 40.16 / 35.91 N
  against 43.30 / 39.14 N (7.3 % and 8.2 % low), status 0, 0 iterations; at 2001
  nodes 2.1 % low;
* 100 m line of 24 N/m to (80, 0, -20), EA 1e13 and 1e15: 12 N at both ends (the
  half-element weight) against 1722.7 / 1242.7 N, status 0; the same line 1 mm long:
  143x low, status 0;
* MoorPy's 500 m line (800 N/m, EA 7.51e11) on a 210 m seabed: 400 iterations, not
  converged (nodal force 1.5e11 N); its sloped-seabed mirror line at 1001 nodes:
  status 0 with the anchor force 99.4 % off.
After: the wire within 2.7e-7 (1001 nodes, 1 iteration) and 6.7e-8 (2001); EA 1e13,
1e15 and the 1 mm line within 1.04e-5, the lumping error of 100 elements (2
iterations); the seabed line within 1.2e-4 at 100 elements (5 iterations, 14 ms).

Tolerance: lumped weight on straight elements errs by c (h/L)^2 with c below 0.2 on
these sagging lines (measured 1.04e-5 at 100 elements: c = 0.1), so 0.5 (h/L)^2 + 1e-9
leaves a factor 5.
"""

from __future__ import annotations

import numpy as np
import pytest

from .test_moorpy_catenary import solve


def line(length: float, ea: float, b: tuple, *, nodes: int, w: float = 24.0) -> dict:
    return {
        "name": "x",
        "environment": {"fluid": "water"},
        "line": {
            "segments": [
                {"length": length, "diameter": 0.05, "weight_in_fluid": w, "axial_stiffness": ea}
            ]
        },
        "ends": {
            "a": {"kind": "fixed", "position": [0.0, 0.0, 0.0]},
            "b": {"kind": "fixed", "position": list(b)},
        },
        "analysis": {"static": {"method": "discrete", "nodes": nodes}, "time_limit": 120.0},
    }


def error(data: dict) -> float:
    out = solve(data)
    ref = solve({**data, "analysis": {"static": {"method": "catenary", "nodes": 11}}})
    return abs(float(out["tension_b"]) / float(ref["tension_b"]) - 1.0)


CASES = [
    ("wire-1001", 2.0, 6.283e7, (1.85, 0.0, -0.172), 1001),
    ("wire-2001", 2.0, 6.283e7, (1.85, 0.0, -0.172), 2001),
    *[(f"ea-{ea:g}", 100.0, ea, (80.0, 0.0, -20.0), 101) for ea in (1.0, 1.0e3, 1e8, 1e13, 1e15)],
    *[(f"length-{s:g}", 100.0 * s, 1e9, (80.0 * s, 0.0, -20.0 * s), 101) for s in (1e-5, 1e3)],
    *[(f"nodes-{n}", 100.0, 1e9, (80.0, 0.0, -20.0), n) for n in (2, 3, 5000)],
]


@pytest.mark.parametrize(("name", "length", "ea", "b", "nodes"), CASES, ids=[c[0] for c in CASES])
def test_discrete_is_right_where_it_was_wrong(name, length, ea, b, nodes) -> None:  # noqa: ANN001
    # light lines where EA is small: EA 1e3 N at 2.4 N/m and EA 1 N at 1e-4 N/m, both
    # strained by about 20 % and 1 %
    w = 24.0 if ea > 1e4 else (2.4 if ea > 10.0 else 1e-4)
    err = error(line(length, ea, b, nodes=nodes, w=w))
    assert err < 0.5 / (nodes - 1) ** 2 + 1e-9, err


def test_discrete_error_falls_as_h_squared() -> None:
    """The fitted order of the end tension's error under mesh halving is 2 (+-0.2)."""
    errs = [error(line(100.0, 1e9, (80.0, 0.0, -20.0), nodes=n)) for n in (21, 41, 81, 161)]
    order = -np.polyfit(np.log([20, 40, 80, 160]), np.log(errs), 1)[0]
    assert abs(order - 2.0) < 0.2, (order, errs)


def test_dynamic_start_of_a_chain_on_the_seabed_at_10_m_elements() -> None:
    """The discrete start of the dynamics of a 250 m chain (126 kg/m, EA 5.8e8) from
    (0, 0, -50) on a 50 m seabed to (230, 0, -5) at 25 elements failed with a residual
    of 5.65e6 N (Newton on positions from the cable solution: EA times its chords'
    error). The positions-and-tensions Newton finds it; the fairlead tension of the
    lumped model is within its O(h^2) lumping error of the cable's, 0.5 % at 10 m
    elements (measured 0.31 %)."""
    import yaml

    from cablestudy.analyses.line_model import discrete_statics
    from cablestudy.dynamics.assembly import evaluate
    from cablestudy.statics import STATIC_SOLVERS
    from cablestudy.study.grid import expand_cases
    from cablestudy.study.loader import parse_study_text
    from cablestudy.study.problem import static_problem

    data = {
        "name": "chain",
        "environment": {"fluid": "water", "depth": 50.0},
        "line": {
            "segments": [
                {
                    "length": 250.0,
                    "diameter": 0.1,
                    "mass_per_length": 126.0,
                    "axial_stiffness": 5.8e8,
                }
            ]
        },
        "ends": {
            "a": {"kind": "fixed", "position": [0.0, 0.0, -50.0]},
            "b": {"kind": "fixed", "position": [230.0, 0.0, -5.0]},
        },
        "analysis": {
            "static": {"method": "catenary", "nodes": 101},
            "dynamic": {
                "elements": 25,
                "excitation": {
                    "end": "b",
                    "direction": [1, 0, 0],
                    "amplitude": 0.5,
                    "frequency": 0.1,
                },
                "method": "time",
            },
        },
    }
    src = parse_study_text(yaml.safe_dump(data, sort_keys=False), "<chain>")
    _, cases = expand_cases(src)
    static = STATIC_SOLVERS["catenary"].solve(static_problem(cases[0].study))
    line, x, msg, anchor = discrete_statics(cases[0], static)
    assert msg == "", msg
    work = evaluate(line, x, np.zeros_like(x), anchor=anchor)
    free = ~line.held
    assert np.max(np.abs(work.F[free])) < 1e-6 * float(np.max(static.tension))
    fairlead = float(np.linalg.norm(work.F[-1]))
    assert abs(fairlead / float(np.linalg.norm(static.force_b)) - 1.0) < 5e-3


CHAIN = {
    "name": "chain",
    "environment": {"fluid": "water", "depth": 50.0},
    "line": {
        "segments": [
            {"length": 250.0, "diameter": 0.1, "mass_per_length": 126.0, "axial_stiffness": 5.8e8}
        ]
    },
    "ends": {
        "a": {"kind": "fixed", "position": [0.0, 0.0, -50.0]},
        "b": {"kind": "fixed", "position": [230.0, 0.0, -5.0]},
    },
    "analysis": {"static": {"method": "catenary", "nodes": 101}},
}


@pytest.mark.parametrize("nodes", [14, 26, 51])
def test_discrete_statics_of_a_chain_on_the_seabed_at_elements_up_to_20_m(nodes: int) -> None:
    """The chain of the dynamics start above, as the static method, at 19.2, 10 and 5 m
    elements: converged, with the fairlead tension within 3 (h/L)^2 of the cable's
    (lumping O(h^2), its constant larger than on a free-hanging line because the
    touchdown sits at a node: measured 1.4e-2, 3.1e-3 and 8.7e-5)."""
    ref = solve(CHAIN)
    data = {**CHAIN, "analysis": {"static": {"method": "discrete", "nodes": nodes}}}
    out = solve(data)
    err = abs(float(out["tension_b"]) / float(ref["tension_b"]) - 1.0)
    assert err < 3.0 / (nodes - 1) ** 2, err
