"""Every study is expanded as a grid (the template validated once, each swept value once,
the other swept values copied into the template or, where they cannot be, each
combination validated as a whole): each case's study must be the one a full validation
of the case's own study file gives, for every study of configs/."""

from __future__ import annotations

from pathlib import Path

import pytest

from cablestudy.cli import main
from cablestudy.study.cases import _copy_tree, _set_path, case_hashes
from cablestudy.study.grid import expand_grid
from cablestudy.study.loader import parse_study_text, read_study_source, validate_data

CONFIGS = sorted((Path(__file__).resolve().parents[2] / "configs").glob("*.yaml"))


def _full(src, grid, index):  # noqa: ANN001, ANN202
    data = _copy_tree({k: v for k, v in src.data.items() if k != "sweep"})
    for axis, a in enumerate(grid.axes):
        for path, vals in zip(a.paths, a.values, strict=True):
            _set_path(data, path, _copy_tree(vals[index[axis]]))
    return validate_data(data, src)


@pytest.mark.parametrize("path", CONFIGS, ids=[p.stem for p in CONFIGS])
def test_every_case_of_the_grid_is_its_fully_validated_study(path: Path) -> None:
    src = read_study_source(path)
    grid = expand_grid(src)
    cases = grid.cases()
    assert len(cases) == grid.size
    full = {case.index: case_hashes(_full(src, grid, case.index)) for case in cases}
    for case in cases:
        # the content hashes of case_hashes cover every validated setting with its
        # defaults filled in: equal hashes, equal studies
        assert case_hashes(case.study) == full[case.index]
    # the grid's own hashes (template and swept values) group the cases as the content
    # hashes do: a case's cache entry, and the static solution cases share
    for k in (0, 1):
        by_grid: dict[str, set] = {}
        by_content: dict[str, set] = {}
        for case in cases:
            by_grid.setdefault((case.hash, case.static_hash)[k], set()).add(case.index)
            by_content.setdefault(full[case.index][k], set()).add(case.index)
        assert sorted(map(sorted, by_grid.values())) == sorted(map(sorted, by_content.values()))


def test_a_swept_period_is_validated_as_a_whole_study(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """A harmonic excitation given by its period derives its frequency (a validator
    before the fields): the period cannot be copied into the template."""
    text = """\
name: per
environment: {fluid: water, depth: 100.0}
line:
  segments:
    - {length: 120.0, diameter: 0.1, mass_per_length: 20.0, axial_stiffness: 1.0e8}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -100.0]}
  b: {kind: fixed, position: [100.0, 0.0, 0.0]}
analysis:
  static: {nodes: 21}
  dynamic:
    method: frequency
    elements: 10
    excitation: {end: b, direction: [1.0, 0.0, 0.0], amplitude: 0.5, period: 10.0}
sweep:
  analysis.dynamic.excitation.period: [8.0, 12.0]
"""
    src = parse_study_text(text, "per.yaml")
    grid = expand_grid(src)
    assert grid.whole == ("analysis.dynamic.excitation.period",)
    freqs = [c.study.analysis.dynamic.excitation.frequency for c in grid.cases()]
    assert freqs == [1.0 / 8.0, 1.0 / 12.0]
    # `cablestudy validate` says which paths are validated as whole studies
    study = tmp_path / "per.yaml"
    study.write_text(text)
    assert main(["validate", str(study)]) == 0
    out = capsys.readouterr().out
    assert "2 cases (period=2)" in out
    assert "validated as whole studies" in out and "analysis.dynamic.excitation.period" in out
