"""Mooring system dynamics against MoorDyn (issue 24): MoorPy's ``tests/case8.dat``
(three polyester legs with bridles to a spar) with the spar surged 2 m at 0.1 Hz,
every line's maximum and minimum tension at both ends against MoorDyn's converged
values (``tests/data/moordyn_system_refs/case8_surge.json``, made by
``benchmarks/make_moordyn_system_refs.py`` on branch ``sysref``: MoorDyn 2.7.2 refined
until its extremes moved less than 2e-3 of the largest tension).

Tolerance: the issue asks for 2 %. Ours at 10 elements per line and 64 steps a period
is 4.6e-4 of the largest tension from our own converged run (80 elements, 256 steps;
docs/guide/systems.md); MoorDyn's reference carries its own 2e-3; per value, relative
to each tension, the two add to under 5e-3 (measured 1.5e-3): 1e-2, half the issue's
bound, leaves room without hiding a modelling difference (a missing added mass or drag
term moves the bridles' extremes by several per cent)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from cablestudy.cases import expand_cases
from cablestudy.config import parse_study_text
from cablestudy.system_cases import evaluate_system_case

ROOT = Path(__file__).parents[2]
REFS = ROOT / "tests" / "data" / "moordyn_system_refs" / "case8_surge.json"


def test_case8_surge_against_moordyn() -> None:
    if not REFS.is_file():
        pytest.skip(f"{REFS.relative_to(ROOT)} (MoorDyn's reference, branch sysref) is absent")
    ref = json.loads(REFS.read_text())
    assert ref["excitation"]["dof"] == "surge" and ref["excitation"]["amplitude"] == 2.0
    text = (ROOT / "configs" / "system-case8-surge.yaml").read_text()
    text = text.replace("elements: 20", "elements: 10").replace(
        "points_per_period: 128", "points_per_period: 64"
    )
    (_, [case]) = expand_cases(parse_study_text(text, "case8.yaml"))
    rec = evaluate_system_case(case)
    assert rec.status == 0, rec.message
    # the reference's lines are MoorDyn's line ids 1..9, ours the imported "1".."9"
    assert [str(line["id"]) for line in ref["lines"]] == list(case.study.lines)
    for key, values in ref["reference"].items():
        np.testing.assert_allclose(rec.data[key], values, rtol=1e-2, err_msg=key)
