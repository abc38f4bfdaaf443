"""Modal analysis of a mooring line resting on a seabed with friction.

For small vibrations static friction holds the laid line (it sticks), so the line must
vibrate like its suspended part alone, pinned at the touchdown point. Independent
check: the same suspended catenary set up as its own study (end A fixed at the
touchdown point, length L minus the laid length, the same mooring end) has the same
natural frequencies. Both models are graded lumped-mass chains with a node at the
touchdown point; they differ by how the 200 elements are shared out (the full line
spends a few on the laid part), an O(h^2) mesh difference measured at 4.4e-4 on the
first six modes; 2e-3 allows for it while a touchdown off by one element (the error
before the node was placed at touchdown) gave 1 %.
"""

from __future__ import annotations

import numpy as np
import yaml

from cablestudy.analyses.evaluate import evaluate_case
from cablestudy.analyses.variables import CaseRecord
from cablestudy.study.grid import expand_cases
from cablestudy.study.loader import parse_study_text


def _study(length: float, anchor: list[float], current: bool = False) -> dict:
    env: dict = {"fluid": "water", "depth": 320.0, "seabed": {"friction": 0.5}}
    if current:
        env["current"] = [
            {"z": 0.0, "speed": 0.514, "heading_deg": 0.0},
            {"z": -300.0, "speed": 0.1, "heading_deg": 90.0},
        ]
    return {
        "name": "modal-seabed",
        "environment": env,
        "line": {
            "segments": [
                {"length": length, "diameter": 0.1, "mass_per_length": 60.0, "axial_stiffness": 5e8}
            ]
        },
        "ends": {
            "a": {"kind": "fixed", "position": anchor},
            "b": {"kind": "mooring", "force": [60000.0, 0.0], "z": -8.6},
        },
        "analysis": {"static": {"nodes": 2001}, "modal": {"modes": 6, "elements": 200}},
    }


def _run(data: dict) -> CaseRecord:
    _, cases = expand_cases(parse_study_text(yaml.safe_dump(data), "<modal-seabed>"))
    record = evaluate_case(cases[0])
    assert record.status == 0, record.message
    return record


def test_laid_line_sticks_and_vibrates_like_its_suspended_part() -> None:
    full = _run(_study(800.0, [0.0, 0.0, -320.0]))
    laid = float(full.data["laid_length"])
    assert laid > 300.0  # friction takes the tension out of much of the laid part
    x_touchdown = float(np.interp(laid, full.data["arc_length"], full.data["x"]))
    suspended = _run(_study(800.0 - laid, [x_touchdown, 0.0, -320.0]))
    np.testing.assert_allclose(
        full.data["natural_frequency"], suspended.data["natural_frequency"], rtol=2e-3
    )


def test_laid_line_with_friction_in_a_turning_current_has_modes() -> None:
    """The audit's case (a friction-locked laid part carries zero tension, which left the
    eigenproblem singular): now a clean result."""
    data = _study(800.0, [0.0, 0.0, -320.0], current=True)
    data["ends"]["b"]["force"] = [60000.0, 10000.0]
    record = _run(data)
    f = np.asarray(record.data["natural_frequency"])
    assert np.all(np.isfinite(f)) and np.all(f > 0) and np.all(np.diff(f) >= 0)
