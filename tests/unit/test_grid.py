"""Sweeps as arrays (cablestudy.grid): the same dataset as the case-by-case path, bit
for bit; per-axis validation with the old path's reports for faulty sweeps; streamed
output with a safe chunk cache."""

from __future__ import annotations

from collections import OrderedDict
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cablestudy import analyses
from cablestudy.cases import expand_cases
from cablestudy.config import parse_study_text
from cablestudy.config.loader import StudyError
from cablestudy.grid import evaluate_grid_chunk, expand_grid
from cablestudy.runner import run_grid_study, run_study

TEXT = """\
name: gr
environment: {fluid: water, depth: 50.0}
line:
  segments:
    - {length: 60.0, diameter: 0.02, mass_per_length: 2.466, axial_stiffness: 6.283e7}
    - {length: 40.0, diameter: 0.05, mass_per_length: 8.0, axial_stiffness: 2.0e8}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -10.0]}
  b: {kind: fixed, position: [92.5, 0.0, -8.6]}
analysis:
  static: {method: catenary, nodes: 21}
sweep:
  ends.b.position.0: {start: 60.0, stop: 100.5, num: 7, name: span}
  line.segments.0.axial_stiffness: [1.0e5, 1.0e6, 6.283e7]
  ends.a.position.2: [-10.0, -20.0]
"""


@pytest.fixture(autouse=True)
def _fresh_static_cache(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(analyses, "_STATIC_CACHE", OrderedDict())


def _both(tmp_path: Path, text: str = TEXT) -> tuple[xr.Dataset, xr.Dataset]:
    src = parse_study_text(text, "gr.yaml")
    grid = expand_grid(src)
    assert grid is not None and grid.shape == (7, 3, 2)
    fast = run_grid_study(
        src, grid, tmp_path / "grid", scheduler="synchronous", use_cache=False, progress=False
    )
    axes, cases = expand_cases(src)
    slow = run_study(
        src,
        axes,
        cases,
        tmp_path / "case",
        scheduler="synchronous",
        use_cache=False,
        progress=False,
    )
    return xr.load_dataset(fast.path), xr.load_dataset(slow.path)


#: the same sweep with end A lowered onto a shallower seabed: most cases rest on it (the
#: compiled contact kernel; slack ones and contact between the ends: the general solver)
ON_SEABED = TEXT.replace("depth: 50.0", "depth: 30.0").replace("[-10.0, -20.0]", "[-10.0, -30.0]")
#: the same on a sloped seabed with friction: the compiled contact kernel in both paths
ON_SLOPE = ON_SEABED.replace(
    "depth: 30.0", "depth: 30.0, seabed: {slope_deg: 2.0, slope_heading_deg: 10.0, friction: 0.5}"
)


#: anchored at end B instead (A above): the contact kernel on the reversed line
ON_SEABED_B = (
    ON_SEABED.replace("depth: 30.0", "depth: 30.0, seabed: {friction: 0.5}")
    .replace("[-10.0, -30.0]", "[-10.0, -12.0]")
    .replace("[92.5, 0.0, -8.6]", "[92.5, 0.0, -30.0]")
)


@pytest.mark.parametrize(
    "text",
    [TEXT, ON_SEABED, ON_SLOPE, ON_SEABED_B],
    ids=["free", "on-seabed", "on-sloped-seabed-friction", "anchored-at-b"],
)
def test_array_path_writes_the_case_by_case_dataset_bit_for_bit(tmp_path: Path, text: str) -> None:
    fast, slow = _both(tmp_path, text)
    if text == TEXT:
        assert int((slow["status"] == 0).sum()) == 42  # slack to stretched, all solved
    else:
        assert float(slow["laid_length"].max()) > 0.0  # the seabed path did run
    assert set(fast.variables) == set(slow.variables)
    for name in slow.variables:
        a, b = fast[name], slow[name]
        assert a.dims == b.dims and a.attrs.keys() == b.attrs.keys(), name
        for key, value in a.attrs.items():  # flag_values is an array
            assert np.array_equal(value, b.attrs[key]), (name, key)
        if name == "wall_time":
            continue
        if a.dtype.kind == "f":
            assert a.values.tobytes() == b.values.tobytes(), name
        else:
            assert np.array_equal(a.values, b.values), name
    skip = {"history"}
    assert {k: v for k, v in fast.attrs.items() if k not in skip} == {
        k: v for k, v in slow.attrs.items() if k not in skip
    }
    assert "share" in fast["wall_time"].attrs["long_name"]


def test_a_sweep_the_arrays_cannot_take_is_left_to_the_case_path() -> None:
    # a swept length changes the nodes' arc lengths: not an array sweep
    text = TEXT.replace("ends.a.position.2: [-10.0, -20.0]", "line.segments.1.length: [40.0, 41.0]")
    assert expand_grid(parse_study_text(text, "gr.yaml")) is None
    text = TEXT.replace("method: catenary", "method: analytic")
    assert expand_grid(parse_study_text(text, "gr.yaml")) is None


def test_faulty_swept_values_are_reported_as_before() -> None:
    """A bad swept value or combination leaves the array path; the case path reports it at
    its line with the sweep case, exactly as before."""
    bad_value = TEXT.replace("[1.0e5, 1.0e6, 6.283e7]", "[1.0e5, -1.0e6, 6.283e7]")
    src = parse_study_text(bad_value, "gr.yaml")
    assert expand_grid(src) is None
    with pytest.raises(StudyError) as exc:
        expand_cases(src)
    assert "line.segments.0.axial_stiffness" in str(exc.value)
    # each value valid on its own, but end A below the seabed only with another axis
    below = TEXT.replace("ends.a.position.2: [-10.0, -20.0]", "ends.a.position.2: [-10.0, -60.0]")
    assert expand_grid(parse_study_text(below, "gr.yaml")) is None
    seabed = below.replace("depth: 50.0", "depth: 70.0")
    assert expand_grid(parse_study_text(seabed, "gr.yaml")) is not None


def test_streamed_result_opens_lazily_and_chunks_are_cached(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    from cablestudy import grid as grid_module
    from cablestudy import runner

    monkeypatch.setattr(runner, "GRID_CHUNK_CASES", 12)  # two rows of 6 cases a chunk
    monkeypatch.setattr(runner, "IN_MEMORY_BYTES", 0)  # streamed, as a large study is
    src = parse_study_text(TEXT, "gr.yaml")
    grid = expand_grid(src)
    first = run_grid_study(src, grid, tmp_path, scheduler="synchronous", progress=False)
    files = sorted((tmp_path / ".cache" / "gr").glob("grid-*.npz"))
    assert len(files) == 4  # rows 0-1, 2-3, 4-5, 6
    lazy = xr.open_dataset(first.path, chunks={})
    assert lazy["x"].chunks is not None  # dask-backed: read on demand
    # written with explicit netCDF chunks of whole blocks of cases (two spans)
    assert lazy["x"].encoding["chunksizes"] == (2, 3, 2, 21)
    ref = xr.load_dataset(first.path)
    # the streamed file is the one the in-memory assembly writes
    monkeypatch.setattr(runner, "IN_MEMORY_BYTES", 1 << 30)
    held = run_grid_study(
        src, grid, tmp_path / "held", scheduler="synchronous", use_cache=False, progress=False
    )
    xr.testing.assert_identical(
        xr.load_dataset(held.path).drop_vars("wall_time"),
        ref.drop_vars("wall_time").assign_attrs(history=held_history(held.path)),
    )
    monkeypatch.setattr(runner, "IN_MEMORY_BYTES", 0)
    calls: list[int] = []
    real = grid_module.evaluate_grid_chunk

    def counted(g, lo, hi):  # noqa: ANN001, ANN202
        calls.append(lo)
        return real(g, lo, hi)

    monkeypatch.setattr(grid_module, "evaluate_grid_chunk", counted)
    raw = bytearray(files[1].read_bytes())
    raw[len(raw) // 3] ^= 0x10
    files[1].write_bytes(bytes(raw))
    capsys.readouterr()
    second = run_grid_study(src, grid, tmp_path, scheduler="synchronous", progress=False)
    err = capsys.readouterr().err
    assert err.count("warning: cache file") == 1 and str(files[1]) in err
    assert len(calls) == 1  # only the damaged chunk is recomputed
    lo = calls[0]
    assert second.n_reused == 42 - 6 * (min(lo + 2, 7) - lo)
    got = xr.load_dataset(second.path)
    for name in ref.data_vars:
        if ref[name].dtype.kind == "f" and name != "wall_time":
            assert ref[name].values.tobytes() == got[name].values.tobytes(), name


def test_chunk_evaluation_matches_its_rows(tmp_path: Path) -> None:
    grid = expand_grid(parse_study_text(TEXT, "gr.yaml"))
    chunk = evaluate_grid_chunk(grid, 2, 4)
    assert chunk.n == 2 * 3 * 2 and chunk.data["x"].shape == (12, 21)
    # the span of each case is where its end B lies
    ok = chunk.status == 0
    np.testing.assert_allclose(
        chunk.data["x"][ok, -1], np.repeat(grid.swept["ends.b.position.0"][1][2:4], 6)[ok]
    )
    assert np.allclose(chunk.wall_time, chunk.wall_time[0])  # the chunk's time shared out


def test_array_chunks_on_worker_processes_give_the_serial_result(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from cablestudy import runner

    monkeypatch.setattr(runner, "GRID_CHUNK_CASES", 12)
    src = parse_study_text(TEXT, "gr.yaml")
    grid = expand_grid(src)
    par = run_grid_study(
        src,
        grid,
        tmp_path / "p",
        scheduler="processes",
        workers=2,
        use_cache=False,
        progress=False,
    )
    ser = run_grid_study(
        src, grid, tmp_path / "s", scheduler="synchronous", use_cache=False, progress=False
    )
    assert par.scheduler == "processes" and ser.scheduler == "synchronous"
    a, b = xr.load_dataset(par.path), xr.load_dataset(ser.path)
    xr.testing.assert_identical(
        a.drop_vars("wall_time"), b.drop_vars("wall_time").assign_attrs(history=a.attrs["history"])
    )
    assert not list((tmp_path / "p").glob(".gr-chunks-*"))  # the scratch folder is gone


def test_an_extended_first_axis_reuses_the_cached_chunks(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from cablestudy import grid as grid_module
    from cablestudy import runner

    monkeypatch.setattr(runner, "GRID_CHUNK_CASES", 12)  # two spans a chunk
    spans = "ends.b.position.0: {start: 60.0, stop: 100.5, num: 7, name: span}"
    short = TEXT.replace(spans, "ends.b.position.0: {values: [60.0, 70.0, 80.0, 90.0], name: span}")
    longer = short.replace("[60.0, 70.0, 80.0, 90.0]", "[60.0, 70.0, 80.0, 90.0, 95.0, 100.0]")
    src = parse_study_text(short, "gr.yaml")
    run_grid_study(src, expand_grid(src), tmp_path, scheduler="synchronous", progress=False)
    calls: list[int] = []
    real = grid_module.evaluate_grid_chunk

    def counted(g, lo, hi):  # noqa: ANN001, ANN202
        calls.append(lo)
        return real(g, lo, hi)

    monkeypatch.setattr(grid_module, "evaluate_grid_chunk", counted)
    src2 = parse_study_text(longer, "gr.yaml")
    again = run_grid_study(
        src2, expand_grid(src2), tmp_path, scheduler="synchronous", progress=False
    )
    assert calls == [4] and again.n_reused == 24 and again.n_computed == 12
    # a changed value of another axis changes every chunk
    other = longer.replace("[-10.0, -20.0]", "[-10.0, -25.0]")
    src3 = parse_study_text(other, "gr.yaml")
    calls.clear()
    run_grid_study(src3, expand_grid(src3), tmp_path, scheduler="synchronous", progress=False)
    assert calls == [0, 2, 4]


def held_history(path: Path) -> str:
    with xr.open_dataset(path) as ds:
        return str(ds.attrs["history"])


def test_the_default_method_takes_the_array_path_as_the_written_one(tmp_path: Path) -> None:
    """Which path a study takes is decided from the validated study, defaults included:
    leaving out ``method: catenary`` (the default) must not send a sweep case by case."""
    from cablestudy.cli import _load
    from cablestudy.grid import CaseGrid

    written, left_out = tmp_path / "written.yaml", tmp_path / "left_out.yaml"
    written.write_text(TEXT)
    left_out.write_text(TEXT.replace("method: catenary, ", ""))
    (_, _, a), (_, _, b) = _load(str(written)), _load(str(left_out))
    assert isinstance(a, CaseGrid) and isinstance(b, CaseGrid)
    assert a.key == b.key  # the same template with its defaults: the same cases, one cache
