"""Mooring system dynamics against MoorDyn (issue 24): every reference of
``tests/data/moordyn_system_refs`` (made by ``benchmarks/make_moordyn_system_refs.py``:
MoorDyn 2.7.2 refined until its extremes moved less than 2e-3 of the line end's maximum
tension; the motion ramped over two periods; the last of eight periods): every line's
maximum and minimum tension at both ends.

- MoorPy's ``tests/case8.dat`` (three polyester legs with bridles to a spar), the spar
  surged 2 m and heaved 1 m at 0.1 Hz (``configs/system-case8-surge.yaml``);
- MoorDyn's ``tests/Mooring/lines.txt`` (OC3-Hywind: three 902 m chains, 135 m of each
  on the seabed), imported as a user imports it, its fairleads moved as one rigid body:
  surge 5 m at 0.05 Hz, pitch 3 deg about (0, 0, 0) at 0.05 Hz and at 0.1 Hz.

Each runs at the coarsest mesh (elements per line x steps a period) converged well
within the bar. Convergence, the largest difference of the 36 (case8) or 12 (lines.txt)
extremes from our finest mesh, relative to each extreme (measured 2026-11-27 by
``benchmarks/system_dynamics_refs_convergence.py``; the same tables in
docs/guide/systems.md):

case8 heave, against 80 x 256:

| mesh | 5x32 | 5x64 | 10x64 | 10x128 | 20x64 | 20x128 | 40x128 | 40x256 |
|---|---|---|---|---|---|---|---|---|
| vs finest | 4.5e-4 | 4.5e-4 | 2.1e-4 | 2.1e-4 | 9.0e-5 | 8.9e-5 | 3.0e-5 | 3.0e-5 |
| vs MoorDyn | 4.8e-4 | 4.8e-4 | 2.4e-4 | 2.4e-4 | 1.2e-4 | 1.2e-4 | 5.7e-5 | 5.6e-5 |

lines.txt surge, against 320 x 512 (the seabed contact moves by whole elements: first
order in the element length):

| mesh | 20x128 | 40x128 | 80x64 | 80x128 | 80x256 | 160x128 | 160x256 |
|---|---|---|---|---|---|---|---|
| vs finest | 2.7e-2 | 7.1e-3 | 3.1e-3 | 3.8e-4 | 6.8e-4 | 2.6e-4 | 1.1e-4 |
| vs MoorDyn | 2.7e-2 | 6.9e-3 | 3.1e-3 | 4.2e-4 | 5.2e-4 | 2.0e-4 | 1.3e-4 |

lines.txt pitch 0.05 Hz, against 320 x 512:

| mesh | 20x128 | 40x64 | 40x128 | 40x256 | 80x128 | 80x256 | 160x128 |
|---|---|---|---|---|---|---|---|
| vs finest | 4.3e-3 | 1.4e-3 | 9.7e-4 | 1.1e-3 | 2.8e-4 | 1.5e-4 | 1.6e-4 |
| vs MoorDyn | 4.3e-3 | 1.4e-3 | 9.7e-4 | 1.1e-3 | 2.7e-4 | 2.1e-4 | 1.8e-4 |

lines.txt pitch 0.1 Hz, against 640 x 1024 (leg 1's anchor minimum, 112 kN as the chain
lands on the seabed at the anchor, sets every entry; the others are within 3e-3 from
80 elements):

| mesh | 80x256 | 160x256 | 320x256 | 320x512 | 640x256 | 640x512 |
|---|---|---|---|---|---|---|
| vs finest | 8.8e-2 | 1.9e-2 | 1.9e-3 | 2.6e-3 | 1.1e-3 | 2.3e-4 |
| leg 1 anchor min [kN] | 102.6 | 110.0 | 112.4 | 112.2 | 112.3 | 112.5 |

Tolerances: the issue asks for 2 % of MoorDyn's value. For the three 0.05-0.1 Hz cases
the bar is 1e-2: our mesh error at the chosen mesh (at most 4e-4, the tables), the
reference's own (its last refinement change, at most 3.3e-4 of a line end's maximum,
1.3e-3 of the smallest minimum, lines.txt surge's 304 kN against 1207 kN) and the
steady-state window's (our run stops when two periods agree to 2e-3 of the largest
tension; MoorDyn's window is its eighth period) add to under 5e-3 per value (measured
4.2e-4 at most): half the issue's bound. What it catches (measured): the normal drag
halved moves case8 surge's extremes by 4.4 %, lines.txt's by 21 % (pitch) and 56 %
(surge); the added mass removed moves them by 0.2-0.5 % only (these motions are
dominated by drag and stiffness, so this check does not resolve the added mass: the
single-line tests do); case8 heave is quasi-static (both changes 3e-4).

At 0.1 Hz in pitch the reference's own error exceeds that on one value: MoorDyn's leg 1
anchor minimum rises 101.6, 107.1, 109.9 kN from 80 to 320 segments (changes halving:
first order, as its README says), so it is still 2.6 % short; its first-order
(Richardson) extrapolation 2 T_320 - T_160 = 112.7 kN is the value to compare (ours
112.3 kN, 0.4 %). That value is held to the issue's 2 % of the extrapolation, the
other eleven to 2 % of the reference (measured 3e-3 at most).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from cablestudy.analyses.system import evaluate_system_case
from cablestudy.study import parse_study_text
from cablestudy.study.grid import expand_cases

ROOT = Path(__file__).parents[2]
REFS = ROOT / "tests" / "data" / "moordyn_system_refs"
KEYS = ("tension_max_a", "tension_min_a", "tension_max_b", "tension_min_b")
LINES_TXT = "moordyn/tests/Mooring/lines.txt"


def study_text(name: str, elements: int, steps: int) -> str:
    """The study of reference ``name`` as a user writes it: case8's config with the
    reference's motion, or lines.txt imported (``cablestudy import``) with an
    ``analysis.dynamic`` moving its fairleads' body as the reference does."""
    ref = json.loads((REFS / f"{name}.json").read_text())
    ex = ref["excitation"]
    assert ex["ramp"].endswith("over t_r = 2 periods") and ex["reference_point"] == [0, 0, 0]
    if name.startswith("case8"):
        text = (ROOT / "configs" / "system-case8-surge.yaml").read_text()
        text = text.replace(
            "dof: surge, amplitude: 2.0", f"dof: {ex['dof']}, amplitude: {ex['amplitude']!r}"
        )
    else:
        from cablestudy.interchange import import_model, imported_yaml

        path = ROOT / "tests" / "data" / LINES_TXT
        imported = import_model(path.read_text(), LINES_TXT, folder=path.parent)
        text = imported_yaml(imported, LINES_TXT) + (
            "  dynamic:\n"
            f"    excitation: {{body: vessel, dof: {ex['dof']}, amplitude: "
            f"{ex['amplitude']!r}, frequency: {ex['frequency']!r}}}\n"
            "    elements: 20\n    points_per_period: 128\n"
        )
    text = text.replace("elements: 20", f"elements: {elements}")
    return text.replace("points_per_period: 128", f"points_per_period: {steps}")


def run_against(name: str, elements: int, steps: int) -> tuple[dict, dict]:
    """Our outputs at the mesh and MoorDyn's reference file."""
    ref = json.loads((REFS / f"{name}.json").read_text())
    (_, [case]) = expand_cases(parse_study_text(study_text(name, elements, steps), "x.yaml"))
    rec = evaluate_system_case(case)
    assert rec.status == 0, rec.message
    # the reference's lines are MoorDyn's line ids, ours the imported names, same order
    assert [str(line["id"]) for line in ref["lines"]] == list(case.study.lines)
    return rec.data, ref


@pytest.mark.parametrize(
    ("name", "elements", "steps"),
    [
        ("case8_surge", 10, 64),
        ("case8_heave", 10, 64),
        ("lines_surge", 80, 128),
        ("lines_pitch", 80, 128),
    ],
)
def test_system_against_moordyn(name: str, elements: int, steps: int) -> None:
    data, ref = run_against(name, elements, steps)
    for key in KEYS:
        np.testing.assert_allclose(data[key], ref["reference"][key], rtol=1e-2, err_msg=key)


def test_lines_pitch_10s_against_moordyn() -> None:
    """Pitch 3 deg at 0.1 Hz: leg 1's anchor minimum against MoorDyn's extrapolated
    value (the module docstring says why), everything else against its reference."""
    data, ref = run_against("lines_pitch_10s", 640, 256)
    levels = ref["refinement"]
    assert levels[-1]["level"] == 2 * levels[-2]["level"]
    extrapolated = 2.0 * levels[-1]["extremes"][0][1] - levels[-2]["extremes"][0][1]
    assert data["tension_min_a"][0] == pytest.approx(extrapolated, rel=2e-2)
    for key in KEYS:
        got = np.asarray(data[key], dtype=float)
        want = np.asarray(ref["reference"][key], dtype=float)
        if key == "tension_min_a":
            got, want = got[1:], want[1:]
        np.testing.assert_allclose(got, want, rtol=2e-2, err_msg=key)
