"""A combination of swept values that the validators of a list they change refuse (a
model's field validator on its list, a validator in the list's annotation) is refused as
a validation of the whole case's study refuses it, though each value alone is valid:
the grid runs those validators again on the list the values were copied into."""

from __future__ import annotations

import pytest

from cablestudy.study.grid import expand_grid
from cablestudy.study.loader import StudyError, parse_study_text

HEAD = """\
name: combos
environment: {fluid: water, depth: 100.0, current: [{z: 0.0, speed: 0.5}, {z: -50.0, speed: 0.2}]}
line:
  segments:
    - {length: 120.0, diameter: 0.1, mass_per_length: 20.0, axial_stiffness: 1.0e8}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -100.0]}
  b: {kind: fixed, position: [100.0, 0.0, -5.0]}
"""

DYNAMIC = """\
analysis:
  dynamic:
    excitation: {end: b, direction: [1.0, 0.0, 1.0], amplitude: 1.0, frequency: 0.1}
"""


def test_two_current_points_swept_to_one_height_are_refused() -> None:
    # z = -20 for both points: Environment's check of distinct heights
    src = parse_study_text(
        HEAD + "sweep:\n  environment.current.0.z: [0.0, -20.0]\n"
        "  environment.current.1.z: {values: [-50.0, -20.0], name: z1}\n",
        "c.yaml",
    )
    with pytest.raises(StudyError) as err:
        expand_grid(src)
    assert "environment.current" in str(err.value)
    # the one case that has it; the axis of a current point's z is current_z (a dimension
    # z would clash with the position output z)
    assert "{'current_z': -20.0, 'z1': -20.0}" in str(err.value)


def test_a_direction_swept_to_zero_in_parts_is_refused() -> None:
    # direction [0, 0, 0] only where both axes take 0 (each alone leaves the other
    # component 1): the direction's own check
    src = parse_study_text(
        HEAD + DYNAMIC + "sweep:\n  analysis.dynamic.excitation.direction.0: [1.0, 0.0]\n"
        "  analysis.dynamic.excitation.direction.2: [1.0, 0.0]\n",
        "d.yaml",
    )
    with pytest.raises(StudyError) as err:
        expand_grid(src)
    assert "direction" in str(err.value) and "nonzero" in str(err.value)
    assert "{'direction_0': 0.0, 'direction_2': 0.0}" in str(err.value)


def test_valid_combinations_pass_and_each_case_holds_its_values() -> None:
    src = parse_study_text(
        HEAD + "sweep:\n  environment.current.0.z: [0.0, -10.0]\n"
        "  environment.current.1.z: {values: [-50.0, -20.0], name: z1}\n",
        "v.yaml",
    )
    grid = expand_grid(src)
    heights = [[p.z for p in c.study.environment.current] for c in grid.cases()]
    assert heights == [[0.0, -50.0], [0.0, -20.0], [-10.0, -50.0], [-10.0, -20.0]]
