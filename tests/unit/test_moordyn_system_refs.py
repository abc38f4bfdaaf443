"""The MoorDyn references of systems driven by a body (tests/data/moordyn_system_refs,
written by benchmarks/make_moordyn_system_refs.py, issue 24): each file converged (the
last refinement changed every extreme by less than 0.2 % of its line end's maximum, and
halving dtM and the motion's hand-over interval at the finest mesh by less than that),
its reference the finest level, and the references as symmetric as the systems are.

Symmetries (a check that would catch a mislabelled line or end):
- case8 is mirror-symmetric about the y-z plane (anchors at x = +-172.7 m, the bridle
  fairleads mirrored): under surge or heave (mirror images of themselves up to the
  sign of surge, which leaves the extremes of a steady periodic response unchanged:
  the mirror image of the response to +X is the response to -X, the same motion half
  a period later) lines 1 and 8, 2 and 7, 3 and 9 have the same extremes, and 4 and 5;
- lines.txt's legs 2 and 3 mirror each other about the x-z plane, the plane of surge
  and pitch: equal extremes.
MoorDyn is deterministic and the mirror systems are its own input, so equal to its
round-off amplified by the steps (measured at most 1e-9 of the extreme): bar 1e-6.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

REFS = Path(__file__).parents[1] / "data" / "moordyn_system_refs"
COLUMNS = ["tension_max_a", "tension_min_a", "tension_max_b", "tension_min_b"]
MIRRORS = {
    "case8_surge": [(1, 8), (2, 7), (3, 9), (4, 5)],
    "case8_heave": [(1, 8), (2, 7), (3, 9), (4, 5)],
    "lines_surge": [(2, 3)],
    "lines_pitch": [(2, 3)],
    "lines_pitch_10s": [(2, 3)],
}


def _load(name: str) -> dict:
    return json.loads((REFS / f"{name}.json").read_text())


@pytest.mark.parametrize("name", sorted(MIRRORS))
def test_reference_converged_and_finest(name: str) -> None:
    ref = _load(name)
    assert ref["converged"], name
    table = ref["refinement"]
    last = table[-1]
    assert last["change_from_previous"] < ref["convergence_bar"] == 2e-3
    assert ref["time_step_check"]["change"] < ref["convergence_bar"]
    assert last["transient"] < 1e-3  # steady: the last two periods agree
    ref_array = np.array([ref["reference"][c] for c in COLUMNS]).T
    np.testing.assert_array_equal(ref_array, np.array(last["extremes"]))
    assert np.all(ref_array[:, 0] >= ref_array[:, 1])  # max >= min at A
    assert np.all(ref_array[:, 2] >= ref_array[:, 3])
    # the errors of the coarser levels are against this reference
    assert last["error"] == 0.0
    assert len(ref["lines"]) == ref_array.shape[0]


@pytest.mark.parametrize("name", sorted(MIRRORS))
def test_reference_symmetric_as_the_system(name: str) -> None:
    ref = _load(name)
    values = np.array([ref["reference"][c] for c in COLUMNS]).T
    ids = [line["id"] for line in ref["lines"]]
    for a, b in MIRRORS[name]:
        va, vb = values[ids.index(a)], values[ids.index(b)]
        np.testing.assert_allclose(va, vb, rtol=1e-6)
