"""Each swept value validated inside the smallest model that holds it
(:func:`cablestudy.study.grid_values.validated_values`) is, bit for bit and type for
type, the value a validation of the whole study gives at that path; where the two could
differ, or the value fails, it answers None and the whole study is validated."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import pytest

from cablestudy.study.cases import _copy_tree, _set_path, parse_sweep
from cablestudy.study.grid import expand_grid
from cablestudy.study.grid_studies import copyable, value_at
from cablestudy.study.grid_values import validated_values
from cablestudy.study.loader import StudyError, parse_study_text, read_study_source, validate_data
from cablestudy.study.study import Study

CONFIGS = sorted((Path(__file__).resolve().parents[2] / "configs").glob("*.yaml"))

LINE = """\
name: t
environment: {fluid: water, depth: 100.0, current: [{z: 0.0, speed: 0.5}]}
line:
  segments:
    - {length: 60.0, diameter: 0.1, mass_per_length: 20.0, axial_stiffness: 1.0e8}
    - {length: 80.0, diameter: 0.1, mass_per_length: 30.0, axial_stiffness: 2.0e8,
       failure: {minimum_breaking_load: 1.0e6}}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -100.0]}
  b: {kind: fixed, position: [100.0, 0.0, -5.0]}
analysis:
  dynamic:
    excitation: {end: b, direction: [1.0, 0.0, 0.0], amplitude: 1.0, frequency: 0.1}
"""

#: sweeps beside those of configs/: values inside the same model swept together, a
#: union chosen by a callable discriminator, integers where floats are read, values
#: that fail (in the model, or only with the rest of the study), paths above a model
#: whose validators could rewrite them
SWEEPS = [
    "zip: [{name: end_b, ends.b.position.0: [90.0, 110.0], ends.b.position.2: [-5, -10.0]}]",
    "analysis.dynamic.excitation.frequency: [0.05, 1, 0.2]",
    "analysis.dynamic.excitation.direction: [[1, 0, 0], [0.0, 0.0, 2.0]]",
    "environment.fluid: [water, air, {density: 1000}]",
    "line.segments.1.length: [70, 90.5]",
    "line.segments.0.axial_stiffness: [1.0e7, -1.0]",  # -1 fails in the segment
    "ends.a.position.2: [-100.0, -150.0]",  # -150 is below the seabed: fails in the study
    "environment.current.0.speed: [0.2, 0.8]",  # Environment checks its current list
    "line.segments.1.failure.minimum_breaking_load: [2.0e6, 3.0e6]",  # through a Segment
    "analysis.static.nodes: [11, 2.5]",  # 2.5 is no count
]


def _same(a: Any, b: Any) -> bool:
    """Equal values of the same types all the way down (the sign of a zero too)."""
    if type(a) is not type(b):
        return False
    if isinstance(a, float):
        return a == b and math.copysign(1.0, a) == math.copysign(1.0, b)
    if isinstance(a, list | tuple):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b, strict=True))
    return bool(a == b)


def _both_ways(src: Any) -> tuple[int, int]:
    """Every swept value validated both ways and compared; (inside a model, as a whole)."""
    template = validate_data(src.data, src)
    base = {k: v for k, v in src.data.items() if k != "sweep"}
    fast = whole = 0
    for axis in parse_sweep(src):
        for i in range(axis.size):
            values = tuple(v[i] for v in axis.values)
            got = validated_values(template, base, axis.paths, values)
            data = _copy_tree(base)
            for path, value in zip(axis.paths, values, strict=True):
                _set_path(data, path, _copy_tree(value))
            try:
                study = validate_data(data, src)
            except StudyError:
                assert got is None, (axis.paths, values)  # a fault: named as a whole study
                whole += 1
                continue
            if got is None:
                whole += 1
                continue
            fast += 1
            for path in axis.paths:
                assert _same(got[0][path], value_at(study, path)), (path, values)
                if copyable(template, path):  # the case's study, as the grid builds it
                    assert _same(value_at(got[1], path), value_at(study, path))
    return fast, whole


@pytest.mark.parametrize("path", CONFIGS, ids=[p.stem for p in CONFIGS])
def test_every_swept_value_of_configs_is_the_whole_studys(path: Path) -> None:
    src = read_study_source(path)
    _both_ways(src)


@pytest.mark.parametrize("sweep", SWEEPS)
def test_swept_values_inside_their_model_or_as_a_whole(sweep: str) -> None:
    src = parse_study_text(LINE + "sweep:\n  " + sweep + "\n", "t.yaml")
    fast, whole = _both_ways(src)
    if "current" in sweep or "failure" in sweep:
        # a field validator of Environment on its current, a validator of Segment
        # before its fields: either could rewrite what is below, so the study is whole
        assert fast == 0
    elif "-1.0]" not in sweep and "-150.0]" not in sweep and "2.5]" not in sweep:
        assert whole == 0  # no fault and nothing above that could rewrite the value


def test_the_frequency_sweep_of_case8_validates_no_whole_study(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """issue 20: the template is validated once, and a swept excitation frequency of a
    system inside its motion, not as 50 whole studies."""
    import cablestudy.study.grid as grid_module

    text = (Path(__file__).resolve().parents[2] / "configs" / "system-case8-surge.yaml").read_text()
    head = text[: text.index("  dynamic:")]
    src = parse_study_text(
        head + "  dynamic:\n    excitation: {body: body1, dof: surge, amplitude: 2.0, "
        "frequency: 0.1}\n    method: frequency\n    elements: 20\n"
        "sweep:\n  analysis.dynamic.excitation.frequency: [0.02, 0.1, 0.5]\n",
        "f.yaml",
    )
    template = validate_data(src.data, src)
    calls = []
    real = grid_module.validate_data
    monkeypatch.setattr(
        grid_module, "validate_data", lambda *a, **k: calls.append(1) or real(*a, **k)
    )
    grid = expand_grid(src, template)
    assert calls == []
    assert [c.study.analysis.dynamic.excitation.frequency for c in grid.cases()] == [
        0.02,
        0.1,
        0.5,
    ]


def test_each_case_study_is_built_once(monkeypatch: pytest.MonkeyPatch) -> None:
    """A single axis: the study its value was checked in is its case's study, built once
    (not again by the cases nor by study_at after them); a chunked grid keeps none of
    them (it never holds its cases' studies)."""
    import cablestudy.study.grid_studies as gs

    built = []
    real = gs._rebuilt

    def counted(node: Any, updates: Any) -> Any:
        if isinstance(node, Study):  # the top of a case's rebuild
            built.append(1)
        return real(node, updates)

    monkeypatch.setattr(gs, "_rebuilt", counted)
    src = parse_study_text(
        LINE + "sweep:\n  analysis.dynamic.excitation.frequency: [0.05, 0.1, 0.2]\n", "t.yaml"
    )
    grid = expand_grid(src)
    cases = grid.cases()
    assert len(built) == 3  # the three studies, one per value
    assert all(grid.study_at(c.index) is c.study for c in cases)
    assert len(built) == 3
    static = LINE.split("analysis:")[0].replace(", current: [{z: 0.0, speed: 0.5}]", "")
    src = parse_study_text(static + "sweep:\n  environment.gravity: [9.79, 9.8, 9.81]\n", "s.yaml")
    grid = expand_grid(src)
    assert grid.chunked and not grid.arrays
    assert not any(isinstance(v, Study) for v in grid.memo.values())
