"""The force of a line on an anchor resting on the seabed in the time domain
(dynamics/end_support.py): the line's pull, not its end node's half element weight
(the seabed carries it, as the statics' laid line) nor the penalty seabed's push."""

from __future__ import annotations

from pathlib import Path

from tests.system_contract import run_study

STUDY = """\
name: laid
environment: {fluid: water, depth: 100.0}
line:
  segments:
    - {length: 360.0, diameter: 0.1, mass_per_length: 60.0, axial_stiffness: 6.0e8}
ends:
  a: {kind: fixed, position: [-300.0, 0.0, -100.0]}
  b: {kind: fixed, position: [0.0, 0.0, -10.0]}
analysis:
  static: {nodes: 11}
  dynamic:
    excitation: {end: b, direction: [1, 0, 0], amplitude: 0.001, frequency: 0.05}
    method: time
    elements: 10
    points_per_period: 32
    max_periods: 6
"""


def test_an_anchor_on_the_seabed_at_rest_feels_the_laid_line_s_tension(tmp_path: Path) -> None:
    """A 360 m chain, 251 m of it laid on a frictionless seabed, end B moved 1 mm (at
    rest to 1e-4 of the tension). The laid part carries its tension unchanged to the
    anchor (no friction), so the force of the line on the anchor is the laid elements'
    tension (at s = 36 m, on the seabed): at 10 elements equal to 1e-6 (round-off and
    the penalty seabed's sinking; measured 1e-9), where the old law added the end
    node's half element weight (18 m of chain, 9.2 kN across 8.2 kN: 50 % more). At 160
    elements it is the statics' tension at the anchor to the discrete model's error
    (measured 1.8e-4, 1e-2 at 40 elements; bound 5e-4, against the old law's 1.3e-3
    more from the half element's 0.58 kN across 10.4 kN)."""
    for elements, key in ((10, "laid"), (160, "static")):
        ds = run_study(
            tmp_path,
            STUDY.replace("elements: 10", f"elements: {elements}").replace(
                "name: laid", f"name: laid{elements}"
            ),
        )
        assert int(ds["status"]) == 0, str(ds["message"].values)
        static = float(ds["tension"].isel(s=0))
        assert float(ds["laid_length"]) > float(ds["s"][1])
        for v in ("tension_envelope_min", "tension_envelope_max"):
            end, laid = float(ds[v].isel(s=0)), float(ds[v].isel(s=1))
            if key == "laid":
                assert abs(end - laid) < 1e-6 * laid, (v, end, laid)
            else:
                assert abs(end - static) < 5e-4 * static, (v, end, static)
