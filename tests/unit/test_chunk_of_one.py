"""A case alone is a chunk of one through the same code, with the same record bit for bit
(issue 20, "Tests"): for every analysis kind, the records of a sweep evaluated as one
chunk -- where compatible statics are solved as one batch and the frequency-domain cases
that share a linear model together (:func:`cablestudy.analyses.evaluate.evaluate_chunk`) -- equal
those of each case evaluated as a chunk of one: status, message, warning and every
output, to the bit. The static-solution caches are emptied before each evaluation, so
that equal statics are equal by computation, not by reuse."""

from __future__ import annotations

from collections import OrderedDict
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cablestudy.analyses import evaluate as analyses
from cablestudy.analyses import line_model
from cablestudy.analyses import static as static_analysis
from cablestudy.analyses.grid_chunk import join_chunks, records_chunk
from cablestudy.analyses.variables import CaseRecord
from cablestudy.study.grid import expand_cases
from cablestudy.study.loader import parse_study_text

CABLE = """\
name: one
environment: {fluid: water}
line:
  segments:
    - {length: 10.9774, diameter: 0.01, mass_per_length: 0.61, axial_stiffness: 7.854e6}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [10.792, 0.0, 0.0]}
analysis:
"""
EXCITATION = (
    "    excitation: {end: b, direction: [1.0, 0.0, 0.0], amplitude: 0.02, frequency: 0.5}\n"
)
KINDS = {
    # lines hanging free and lines on the seabed, solved as one batch in the chunk
    "static": (
        CABLE.replace("{fluid: water}", "{fluid: water, depth: 5.0}")
        + "  static: {nodes: 21}\n"
        + "sweep:\n  ends.b.position.0: [9.0, 10.0, 10.792]\n"
        + "  ends.a.position.2: [-5.0, -2.0]\n"
    ),
    "modal": (
        CABLE
        + "  static: {method: analytic, nodes: 21}\n  modal: {modes: 3, elements: 20}\n"
        + "sweep:\n  ends.b.position.0: [10.6, 10.792]\n"
        + "  line.segments.0.axial_stiffness: [1.0e6, 7.854e6]\n"
    ),
    # cases differing only in the excitation share one linear model: one batched solve
    "frequency": (
        CABLE
        + "  static: {method: analytic, nodes: 21}\n  dynamic:\n"
        + EXCITATION
        + "    method: frequency\n    elements: 10\n"
        + "sweep:\n  analysis.dynamic.excitation.frequency: [0.3, 0.5, 0.9]\n"
        + "  analysis.dynamic.excitation.amplitude: [0.01, 0.02]\n"
    ),
    "time": (
        CABLE
        + "  static: {method: analytic, nodes: 21}\n  dynamic:\n"
        + EXCITATION
        + "    method: time\n    elements: 10\n"
        + "sweep:\n  analysis.dynamic.excitation.amplitude: [0.01, 0.02]\n"
    ),
    "database": (
        CABLE
        + "  static: {method: catenary, nodes: 21}\n  database:\n"
        + "    horizontal_distance: {start: 10.0, stop: 10.7, num: 4}\n"
        + "    height_difference: {start: -1.0, stop: 0.0, num: 4}\n"
        + "sweep:\n  line.segments.0.axial_stiffness: [1.0e6, 7.854e6]\n"
    ),
}


def _fresh(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(static_analysis, "_STATIC_CACHE", OrderedDict())
    monkeypatch.setattr(line_model, "_DISCRETE_CACHE", OrderedDict())


def _same(a: CaseRecord, b: CaseRecord) -> None:
    assert (a.status, a.message, a.warning, a.fallback) == (
        b.status,
        b.message,
        b.warning,
        b.fallback,
    )
    assert a.data.keys() == b.data.keys()
    for name, value in a.data.items():
        x, y = np.asarray(value), np.asarray(b.data[name])
        assert x.dtype == y.dtype and x.shape == y.shape, name
        if x.dtype.kind in "fc":
            assert x.tobytes() == y.tobytes(), name  # to the bit, NaN included
        else:
            assert np.array_equal(x, y), name


@pytest.mark.parametrize("kind", list(KINDS))
def test_a_case_alone_gives_the_record_it_gets_in_its_chunk(
    kind: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    src = parse_study_text(KINDS[kind], "one.yaml")
    _, cases = expand_cases(src)
    assert len(cases) >= 2
    _fresh(monkeypatch)
    together = analyses.evaluate_chunk(cases)
    alones = []
    for case, record in zip(cases, together, strict=True):
        _fresh(monkeypatch)
        (alone,) = analyses.evaluate_chunk([case])
        _same(record, alone)
        alones.append(alone)
    # ... and in the chunk form the runner stores and assembles (records_chunk, in the
    # worker): the chunk of the sweep equals its chunks of one joined, to the bit
    whole = records_chunk(together)
    joined = join_chunks([records_chunk([a]) for a in alones])
    for column in ("status", "message", "warning", "fallback_reason", "hashes"):
        assert np.array_equal(getattr(whole, column), getattr(joined, column)), column
    assert whole.data.keys() == joined.data.keys()
    for name, x in whole.data.items():
        y = joined.data[name]
        assert x.dtype.kind == y.dtype.kind and x.shape == y.shape, name
        assert x.tobytes() == y.tobytes() if x.dtype.kind == "f" else np.array_equal(x, y), name
    assert all(r.status == 0 for r in together)  # the sweep exercises the analysis
    present = {k for r in together for k in r.data}
    expect = {
        "static": "laid_length",
        "modal": "natural_frequency",
        "frequency": "tension_amplitude_b",
        "time": "tension_max",
        "database": "database_tension_b",
    }[kind]
    assert any(k.startswith(expect) for k in present), sorted(present)


@pytest.mark.parametrize("kind", ["modal", "frequency", "database"])
def test_a_cached_rerun_of_every_kind_is_the_run_that_filled_it(kind: str, tmp_path: Path) -> None:
    """Every kind's chunks go through the one store: a re-run reuses every case (found by
    its content hash) and writes the same dataset -- and the same database file -- bit
    for bit (wall times included: they are the cached ones)."""
    from cablestudy.run.runner import run_study
    from cablestudy.study.grid import expand_grid

    src = parse_study_text(KINDS[kind], "one.yaml")
    grid = expand_grid(src)
    assert not grid.chunked  # the case path
    first = run_study(src, grid, tmp_path, scheduler="synchronous", progress=False)
    a = xr.load_dataset(first.path)
    files = sorted((tmp_path / ".cache" / "one").glob("grid-*.npz"))
    assert len(files) == 1  # compacted to one file of the study's cases
    second = run_study(src, grid, tmp_path, scheduler="synchronous", progress=False)
    assert (second.n_reused, second.n_computed) == (grid.size, 0)
    b = xr.load_dataset(second.path)
    xr.testing.assert_identical(b.assign_attrs(history=a.attrs["history"]), a)
    for name in a.data_vars:
        if a[name].dtype.kind == "f":
            assert a[name].values.tobytes() == b[name].values.tobytes(), name
    assert (first.database_path is None) == (kind != "database")
    if kind == "database":
        da, db = (xr.load_dataset(p.database_path) for p in (first, second))
        xr.testing.assert_identical(db.assign_attrs(history=da.attrs["history"]), da)
