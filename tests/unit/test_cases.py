"""Sweep expansion into cases: axes and their names, ranges, zip groups, the cartesian
product, frozen cases with coordinates, and content hashes."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from cablestudy.study import parse_study_text
from cablestudy.study.cases import Case, SweepAxis, parse_sweep
from cablestudy.study.grid import expand_cases

BASE = """\
name: sw
description: first
environment: {fluid: air}
line:
  segments:
    - {length: 100.0, diameter: 0.02, mass_per_length: 2.466, axial_stiffness: 6.283e7}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [92.5, 0.0, -8.6]}
analysis:
  static: {method: analytic, nodes: 11}
"""


def expand(sweep: str, base: str = BASE) -> tuple[list[SweepAxis], list[Case]]:
    return expand_cases(parse_study_text(base + sweep, "t.yaml"))


def test_no_sweep_is_one_case_without_dims() -> None:
    axes, cases = expand("")
    assert axes == [] and len(cases) == 1
    assert cases[0].index == () and cases[0].coords == {}


def test_cartesian_product_in_file_order() -> None:
    axes, cases = expand(
        "sweep:\n"
        "  line.segments.0.axial_stiffness: [1.0e6, 1.0e7]\n"
        "  ends.b.position.0: {start: 60.0, stop: 90.0, num: 4}\n"
        "  environment.fluid: [air, vacuum, {density: 1.0}]\n"
    )
    assert [a.name for a in axes] == ["axial_stiffness", "position_0", "fluid"]
    assert [a.size for a in axes] == [2, 4, 3]
    assert len(cases) == 24
    assert [c.index for c in cases[:4]] == [(0, 0, 0), (0, 0, 1), (0, 0, 2), (0, 1, 0)]
    case = cases[-1]  # (1, 3, 2)
    assert case.coords == {"axial_stiffness": 1.0e7, "position_0": 90.0, "fluid": 2}
    assert case.study.line.segments[0].axial_stiffness == 1.0e7
    assert case.study.ends.b.position == [90.0, 0.0, -8.6]
    assert case.study.environment.density == 1.0
    # scalar axes are their own coordinate, with units and a long name from the model
    np.testing.assert_array_equal(axes[1].coordinate(), [60.0, 70.0, 80.0, 90.0])
    assert axes[0].units == "N" and "line.segments.0.axial_stiffness" in axes[0].long_name
    assert axes[1].units == "m"
    # an axis of mappings is indexed
    np.testing.assert_array_equal(axes[2].coordinate(), [0, 1, 2])


def test_step_range_includes_stop_and_explicit_names() -> None:
    axes, _ = expand(
        "sweep:\n"
        "  ends.b.position.0: {start: 60.0, stop: 61.0, step: 0.1, name: span}\n"
        "  line.segments.0.length: {values: [100.0, 110.0], name: L}\n"
    )
    assert [a.name for a in axes] == ["span", "L"]
    np.testing.assert_allclose(axes[0].coordinate(), np.linspace(60.0, 61.0, 11), atol=1e-12)


def test_zip_group_varies_together_on_one_dimension() -> None:
    axes, cases = expand(
        "sweep:\n"
        "  zip:\n"
        "    - name: support\n"
        "      ends.b.position.0: [80.0, 85.0, 90.0]\n"
        "      ends.b.position.2: [-5.0, -6.0, -7.0]\n"
        "  line.segments.0.axial_stiffness: [1.0e6, 1.0e7]\n"
    )
    assert [a.name for a in axes] == ["support", "axial_stiffness"]
    assert len(cases) == 6
    c = next(c for c in cases if c.index == (2, 0))
    assert c.study.ends.b.position == [90.0, 0.0, -7.0]
    assert c.coords["support"] == 2


def test_case_is_frozen_and_hashes_are_content_hashes() -> None:
    _, cases = expand("sweep:\n  line.segments.0.axial_stiffness: [1.0e6, 1.0e7]\n")
    with pytest.raises(dataclasses.FrozenInstanceError):
        cases[0].hash = "x"  # type: ignore[misc]
    assert len({c.hash for c in cases}) == 2
    # stable across expansions; name and description do not enter the hash
    _, again = expand(
        "sweep:\n  line.segments.0.axial_stiffness: [1.0e6, 1.0e7]\n",
        BASE.replace("name: sw", "name: other").replace("first", "second"),
    )
    assert [c.hash for c in cases] == [c.hash for c in again]
    # an explicit default is the same case as an omitted one
    _, explicit = expand(
        "sweep:\n  line.segments.0.axial_stiffness: [1.0e6, 1.0e7]\n",
        BASE.replace("diameter: 0.02,", "diameter: 0.02, drag_normal: 1.2,"),
    )
    assert [c.hash for c in cases] == [c.hash for c in explicit]
    # any setting that affects the result changes it
    _, other = expand(
        "sweep:\n  line.segments.0.axial_stiffness: [1.0e6, 1.0e7]\n",
        BASE.replace("nodes: 11", "nodes: 12"),
    )
    assert not {c.hash for c in cases} & {c.hash for c in other}


def test_static_hash_shared_by_cases_that_differ_only_outside_statics() -> None:
    _, cases = expand("sweep:\n  analysis.time_limit: [100.0, 200.0]\n")
    assert cases[0].hash != cases[1].hash
    assert cases[0].static_hash == cases[1].static_hash


def test_vector_valued_axis() -> None:
    axes, cases = expand("sweep:\n  ends.b.position: [[90.0, 0.0, -5.0], [0.0, 90.0, -5.0]]\n")
    assert axes[0].name == "position" and axes[0].size == 2
    assert cases[1].study.ends.b.position == [0.0, 90.0, -5.0]


def test_parse_sweep_of_an_unchanged_source_is_deterministic() -> None:
    src = parse_study_text(BASE + "sweep:\n  line.segments.0.length: [100.0, 110.0]\n", "t")
    assert parse_sweep(src) == parse_sweep(src)


PATHS = {
    "line.segments.0.axial_stiffness": lambda st: st.line.segments[0].axial_stiffness,
    "line.segments.0.length": lambda st: st.line.segments[0].length,
    "ends.b.position.2": lambda st: st.ends.b.position[2],
}


@settings(max_examples=25, deadline=None)
@given(sizes=st.lists(st.integers(1, 4), min_size=1, max_size=3))
def test_every_case_holds_its_coordinates(sizes: list[int]) -> None:
    """For any sweep, the cases are the full product and each case's study holds, at
    each swept path, the value of its coordinate."""
    paths = list(PATHS)[: len(sizes)]
    lines = [
        f"  {p}: [{', '.join(str(90.0 + 2.0 * i) for i in range(n))}]"
        for p, n in zip(paths, sizes, strict=False)
    ]
    axes, cases = expand("sweep:\n" + "\n".join(lines) + "\n")
    assert len(cases) == int(np.prod(sizes))
    assert len({c.index for c in cases}) == len(cases)
    for case in cases:
        for axis, path in zip(axes, paths, strict=True):
            assert PATHS[path](case.study) == case.coords[axis.name]


def test_zip_group_paths_may_repeat_values() -> None:
    """In a zip group the dimension's coordinate is the case index, so one path may
    repeat a value (the moustafa Figs. 8-10 pairs (0.075 m, 1 Hz) and (0.1 m, 1 Hz))."""
    from cablestudy.study.grid import expand_cases
    from cablestudy.study.loader import parse_study_text

    text = """
name: zipped
line:
  segments:
    - {length: 100.0, diameter: 0.02, mass_per_length: 2.0, axial_stiffness: 1.0e+8}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [90.0, 0.0, 0.0]}
sweep:
  zip:
    - name: case
      line.segments.0.length: [100.0, 101.0, 102.0]
      line.segments.0.diameter: [0.02, 0.03, 0.03]
"""
    axes, cases = expand_cases(parse_study_text(text, "<zip>"))
    assert [a.name for a in axes] == ["case"]
    assert [c.study.line.segments[0].diameter for c in cases] == [0.02, 0.03, 0.03]


def test_labels_are_the_coordinate_and_leave_the_cases_unchanged() -> None:
    """Labels name the values, they do not change them: the labelled sweep gives the
    same studies and case hashes as the unlabelled one, with text coordinates."""
    plain_axes, plain = expand(
        "sweep:\n"
        "  ends.b.position: {values: [[80.0, 0.0, -8.6], [90.0, 0.0, -8.6]], name: place}\n"
        "  zip:\n"
        "    - {name: pair, ends.a.position.2: [0.0, 1.0],\n"
        "       line.segments.0.axial_stiffness: [1.0e6, 1.0e7]}\n"
    )
    axes, cases = expand(
        "sweep:\n"
        "  ends.b.position: {values: [[80.0, 0.0, -8.6], [90.0, 0.0, -8.6]], name: place,\n"
        "                    labels: [near, far]}\n"
        "  zip:\n"
        "    - {name: pair, labels: [low, high], ends.a.position.2: [0.0, 1.0],\n"
        "       line.segments.0.axial_stiffness: [1.0e6, 1.0e7]}\n"
    )
    assert axes[0].labels == ("near", "far") and axes[1].labels == ("low", "high")
    assert axes[0].coordinate().tolist() == ["near", "far"]
    assert plain_axes[0].coordinate().tolist() == [0, 1]  # no labels: the index
    assert axes[1].paths == plain_axes[1].paths  # 'labels' is not taken for a path
    assert [c.hash for c in cases] == [c.hash for c in plain]
    assert cases[3].coords == {"place": "far", "pair": "high"}
    assert tuple(cases[3].study.ends.b.position) == (90.0, 0.0, -8.6)
    assert tuple(cases[3].study.ends.a.position) == (0.0, 0.0, 1.0)


@pytest.mark.parametrize(
    ("sweep", "message"),
    [
        (
            "{values: [1.0e6, 1.0e7], labels: [soft]}",
            "sweep.line.segments.0.axial_stiffness.labels: 1 labels for 2 values; allowed: "
            "one label per value (got ['soft'])",
        ),
        (
            "{values: [1.0e6, 1.0e7], labels: [soft, soft]}",
            "sweep.line.segments.0.axial_stiffness.labels: 'soft' listed twice; allowed: "
            "distinct labels (each becomes one coordinate) (got ['soft', 'soft'])",
        ),
        (
            "{values: [1.0e6, 1.0e7], labels: [soft, 2]}",
            "sweep.line.segments.0.axial_stiffness.labels: must be a list of non-empty "
            "strings without '=', one per swept value (got ['soft', 2])",
        ),
        (
            "{start: 1.0e6, stop: 1.0e7, num: 2, labels: [soft, 'a=b']}",
            "without '='",
        ),
        ("{values: [1.0e6, 1.0e7], labels: null}", "(got None)"),
    ],
)
def test_labels_refused_naming_the_key(sweep: str, message: str) -> None:
    from cablestudy.study import StudyError

    with pytest.raises(StudyError) as err:
        expand(f"sweep:\n  line.segments.0.axial_stiffness: {sweep}\n")
    assert message in str(err.value)


def test_labels_on_a_zipped_path_are_refused() -> None:
    from cablestudy.study import StudyError

    with pytest.raises(StudyError) as err:
        expand(
            "sweep:\n  zip:\n    - name: pair\n"
            "      ends.a.position.2: {values: [0.0, 1.0], labels: [a, b]}\n"
            "      ends.b.position.2: [-8.6, -7.6]\n"
        )
    assert (
        "sweep.zip.0.ends.a.position.2.labels: the labels of a zip group go beside its "
        "name (sweep.zip.0.labels), not on one of its paths"
    ) in str(err.value)


def test_a_name_on_one_path_of_a_zip_group_is_refused() -> None:
    """A zip group is one dimension named beside its paths; a ``name`` on one of its paths
    would be silently ignored, so it is refused naming the key."""
    import pytest as _pytest

    from cablestudy.study.cases import parse_sweep
    from cablestudy.study.loader import StudyError, parse_study_text

    text = """\
name: z
environment: {fluid: air}
line:
  segments:
    - {length: 100.0, diameter: 0.02, mass_per_length: 2.466, axial_stiffness: 6.283e7}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [92.5, 0.0, -8.6]}
sweep:
  zip:
    - name: support
      ends.b.position.0: {values: [90.0, 95.0], name: span}
      ends.b.position.2: [-8.6, -5.0]
"""
    with _pytest.raises(StudyError) as err:
        parse_sweep(parse_study_text(text, "z.yaml"))
    assert "sweep.zip.0.ends.b.position.0.name: the dimension of a zip group is named beside" in (
        str(err.value)
    )
