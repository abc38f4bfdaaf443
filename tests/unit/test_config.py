"""Study models: valid files parse with SI defaults, strict types, derived mass and
weight, and the JSON Schema that editors use."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from cablestudy.cli import main
from cablestudy.study import Study, StudyError, load_study, parse_study_text
from cablestudy.study.environment import FLUID_DENSITY
from cablestudy.study.loader import validate_data

ROOT = Path(__file__).resolve().parents[2]

TEXT = """\
name: ok
environment: {fluid: water, depth: 100.0}
line:
  segments:
    - {length: 60.0, diameter: 0.05, weight_in_fluid: 40.0, axial_stiffness: 1e8}
    - {length: 40.0, diameter: 0.05, mass_per_length: 3.0, axial_stiffness: 2E8}
ends:
  a: {kind: fixed, position: [0, 0, -100]}
  b: {kind: mooring, force: [1000.0, 0.0], z: 0.0}
"""


def _study(text: str = TEXT) -> Study:
    src = parse_study_text(text, "t.yaml")
    return validate_data(src.data, src)


def test_shipped_studies_are_valid() -> None:
    for path in sorted((ROOT / "configs").glob("*.yaml")):
        study, src = load_study(path)
        assert study.name == path.stem, path
        assert src.sha256 and src.text == path.read_text()


def test_defaults_and_scientific_notation_without_a_dot() -> None:
    study = _study()
    # YAML 1.1 would read 1e8 and 2E8 as strings; the loader reads them as numbers
    assert [s.axial_stiffness for s in study.line.segments] == [1e8, 2e8]
    assert study.environment.gravity == 9.80665
    assert study.environment.density == FLUID_DENSITY["water"] == 1025.0
    assert study.analysis.static.nodes == 101
    assert study.environment.current is None and not study.environment.has_current
    # integers are accepted where a number is expected, and stay exact
    assert study.ends.a.position == [0.0, 0.0, -100.0]


def test_mass_and_weight_derived_from_each_other() -> None:
    study = _study()
    rho, g = study.environment.density, study.environment.gravity
    seg_w, seg_m = study.line.segments
    area = math.pi * 0.05**2 / 4
    # weight given: mass = w / g + rho A (Archimedes)
    assert seg_w.mass_in(rho, g) == pytest.approx(40.0 / g + rho * area, rel=1e-15)
    assert seg_w.weight_in(rho, g) == 40.0
    # mass given: w = (m - rho A) g
    assert seg_m.weight_in(rho, g) == pytest.approx((3.0 - rho * area) * g, rel=1e-15)


def test_models_are_frozen() -> None:
    study = _study()
    with pytest.raises(Exception, match="frozen"):
        study.line.segments[0].length = 1.0  # type: ignore[misc]


@pytest.mark.parametrize(
    ("old", "new"),
    [("length: 60.0", "length: true"), ("[0, 0, -100]", "['0', 0, -100]")],
)
def test_no_coercion_of_booleans_or_text(old: str, new: str) -> None:
    with pytest.raises(StudyError, match="must be a number"):
        _study(TEXT.replace(old, new))


def test_buoyant_segment_is_allowed_down_to_zero_mass() -> None:
    # w = -rho g A exactly is a massless buoyant line: allowed; any lighter is not
    rho, g, area = 1025.0, 9.80665, math.pi * 0.05**2 / 4
    ok = TEXT.replace("weight_in_fluid: 40.0", f"weight_in_fluid: {-rho * g * area * 0.999}")
    _study(ok)
    bad = TEXT.replace("weight_in_fluid: 40.0", f"weight_in_fluid: {-rho * g * area * 1.01}")
    with pytest.raises(StudyError, match=r":5: line.segments.0.weight_in_fluid: implies"):
        _study(bad)


def test_slack_weightless_line_is_fine_when_stretched() -> None:
    text = """\
name: spring
environment: {fluid: vacuum}
line:
  segments: [{length: 10.0, diameter: 0.01, weight_in_fluid: 0.0, axial_stiffness: 1e5}]
ends:
  a: {kind: fixed, position: [0, 0, 0]}
  b: {kind: fixed, position: [10.5, 0, 0]}
"""
    _study(text)  # chord 10.5 m > 10 m: a straight spring, solvable
    with pytest.raises(StudyError, match="no weight"):
        _study(text.replace("[10.5, 0, 0]", "[9.5, 0, 0]"))


def test_sloped_seabed_height_is_used_for_fixed_ends() -> None:
    text = TEXT.replace("depth: 100.0}", "depth: 100.0, seabed: {slope_deg: 10.0}}")
    text = text.replace("[0, 0, -100]", "[100, 0, -90]")
    # the seabed rises 100 tan(10 deg) = 17.6 m by x = 100: z = -90 is below it
    with pytest.raises(StudyError, match=r"ends.a.position: end a lies below the seabed"):
        _study(text)
    _study(text.replace("[100, 0, -90]", "[100, 0, -80]"))


def test_schema_command_prints_a_json_schema(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["schema"]) == 0
    schema = json.loads(capsys.readouterr().out)
    assert schema["$schema"].startswith("https://json-schema.org/")
    assert schema["additionalProperties"] is False
    assert set(schema["required"]) == {"name"}
    # one line (line and ends) or a system (lines between points)
    assert {tuple(sorted(alt["required"])) for alt in schema["oneOf"]} == {
        ("ends", "line"),
        ("lines", "points"),
    }
    segment = schema["$defs"]["Segment"]
    assert segment["properties"]["length"]["exclusiveMinimum"] == 0.0
    assert "unstretched length [m]" in segment["properties"]["length"]["description"]
    assert "additionalProperties" in schema["properties"]["sweep"]
