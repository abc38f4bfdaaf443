"""What the static method cannot model is refused before any work for a sweep run as
arrays too: the template answers for every case, since an array grid sweeps only end
positions of fixed ends and segment stiffnesses, which no support check reads (issue 20,
"Speed": checking every swept value's study cost 20 ms of a 0.5 s run)."""

from __future__ import annotations

from pathlib import Path

import pytest

from cablestudy import cli
from cablestudy.analyses import check_supported
from cablestudy.cases import Case, case_hashes
from cablestudy.config.loader import StudyError, read_study_source
from cablestudy.grid import expand_grid
from cablestudy.grid_static import axis_studies

STUDY = """\
name: eib
environment: {fluid: air}
line:
  segments:
    - {length: 100.0, diameter: 0.02, mass_per_length: 2.466, axial_stiffness: 6.283e7,
       bending_stiffness: 10.0}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [92.5, 0.0, -8.6]}
sweep:
  ends.b.position.0: [80.0, 90.0, 95.0]
  line.segments.0.axial_stiffness: [1.0e6, 6.283e7]
"""


def _refusal(studies: list, src: object) -> list[str]:
    with pytest.raises(StudyError) as info:
        check_supported([Case((), {}, st, *case_hashes(st)) for st in studies], src)  # type: ignore[arg-type]
    return info.value.problems


def test_an_array_grid_is_refused_by_its_template_as_by_every_case(tmp_path: Path) -> None:
    path = tmp_path / "eib.yaml"
    path.write_text(STUDY)
    src = read_study_source(str(path))
    grid = expand_grid(src)
    assert grid is not None and grid.arrays
    by_template = _refusal([grid.template], src)
    assert by_template == _refusal(axis_studies(grid), src)
    assert "does not support bending stiffness" in by_template[0]
    with pytest.raises(StudyError) as info:
        cli._load(str(path))
    assert info.value.problems == by_template
