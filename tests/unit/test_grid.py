"""Sweeps as arrays (cablestudy.analyses.static_grid): the same dataset as the case-by-case path,
bit
for bit; per-axis validation with the old path's reports for faulty sweeps; streamed
output with a safe chunk cache."""

from __future__ import annotations

import time
from collections import OrderedDict
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cablestudy.analyses import static as static_analysis
from cablestudy.analyses.static_grid import evaluate_grid_chunk
from cablestudy.analyses.variables import KEPT_STATUSES
from cablestudy.run import grid_runner
from cablestudy.run.runner import run_study
from cablestudy.study import parse_study_text
from cablestudy.study.grid import CaseGrid, expand_grid
from cablestudy.study.loader import StudyError

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
    monkeypatch.setattr(static_analysis, "_STATIC_CACHE", OrderedDict())


def _both(tmp_path: Path, text: str = TEXT) -> tuple[xr.Dataset, xr.Dataset]:
    src = parse_study_text(text, "gr.yaml")
    grid = expand_grid(src)
    assert grid.chunked
    fast = run_study(
        src, grid, tmp_path / "grid", scheduler="synchronous", use_cache=False, progress=False
    )
    slow = run_study(  # the same cases as case records (the path of unchunked grids)
        src,
        replace(grid, chunked=False),
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


#: sweeps of keys no compiled array kernel takes straight from arrays: each case's study
#: is the template with the validated values put in by copying
#: (cablestudy.analyses.static_grid_cases)
SPANS = "ends.b.position.0: {start: 60.0, stop: 100.5, num: 7, name: span}"
STIFF = "line.segments.0.axial_stiffness: [1.0e5, 1.0e6, 6.283e7]"
#: a segment length: every case has its own arc lengths (s becomes the node index)
LENGTHS = TEXT.replace("ends.a.position.2: [-10.0, -20.0]", "line.segments.1.length: [40.0, 47.5]")
#: node counts: arrays of different lengths, padded as the case path pads them
NODES = TEXT.replace(
    "ends.a.position.2: [-10.0, -20.0]", "analysis.static.nodes: [11, 21]"
).replace("method: catenary, nodes: 21", "method: catenary")
#: a current with drag over a seabed (the drag iteration per case, compiled; a line
#: anchored on the seabed that may hang free of it goes to the general solver)
CURRENT = (
    TEXT.replace(
        "environment: {fluid: water, depth: 50.0}",
        "environment:\n  fluid: water\n  depth: 50.0\n"
        "  current: [{z: 0.0, speed: 0.5, heading_deg: 30.0}]",
    )
    .replace("axial_stiffness: 6.283e7}", "axial_stiffness: 6.283e7, drag_normal: 1.2}")
    .replace(SPANS, "ends.b.position.0: [80.0, 95.0]")
    .replace(STIFF, "environment.current.0.speed: [0.0, 0.5, 1.0]")
    .replace("ends.a.position.2: [-10.0, -20.0]", "environment.current.0.heading_deg: [0.0, 90.0]")
)
#: a towed line: end B a known force, swept
FORCE = (
    TEXT.replace("{fluid: water, depth: 50.0}", "{fluid: water}")
    .replace(
        "b: {kind: fixed, position: [92.5, 0.0, -8.6]}",
        "b: {kind: force, force: [2000.0, 0.0, 500.0]}",
    )
    .replace(SPANS, "ends.b.force.0: [500.0, 2000.0, 8000.0]")
    .replace(STIFF, "ends.b.force.2: [-500.0, 0.0, 1500.0]")
    .replace("ends.a.position.2: [-10.0, -20.0]", "line.segments.1.mass_per_length: [8.0, 12.0]")
)
#: friction on the seabed swept, with the depth (end A resting on it)
FRICTION = (
    ON_SEABED.replace("depth: 30.0", "depth: 30.0, seabed: {friction: 0.0}")
    .replace(STIFF, "environment.seabed.friction: [0.0, 0.3, 1.0]")
    .replace("ends.a.position.2: [-10.0, -30.0]", "environment.depth: [30.0, 31.0]")
    .replace(
        "a: {kind: fixed, position: [0.0, 0.0, -10.0]}",
        "a: {kind: fixed, position: [0.0, 0.0, -30.0]}",
    )
)
#: methods without a batch kernel: the registry solver per case, on a small sweep
ONE_SEGMENT = """\
name: gr
environment: {fluid: air}
line:
  segments:
    - {length: 100.0, diameter: 0.02, mass_per_length: 2.466, axial_stiffness: 6.283e7}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [92.5, 0.0, -8.6]}
analysis:
  static: {method: METHOD, nodes: 11}
sweep:
  ends.b.position.0: [80.0, 92.5]
  line.segments.0.mass_per_length: [2.466, 5.0]
"""
ANALYTIC = ONE_SEGMENT.replace("METHOD", "analytic")
DISCRETE = ONE_SEGMENT.replace("METHOD", "discrete")
SHOOTING = ONE_SEGMENT.replace("METHOD", "shooting")
#: a span sweep (end positions only) of a line with a nonlinear law, a buoy and a failure
#: limit: strain from the law and broken cases, so not the compiled array route
POLYNOMIAL = (Path(__file__).parents[2] / "configs" / "cable-polynomial-catenary.yaml").read_text()

#: the attributes only the array path writes: how many cases no batch kernel took
FALLBACK_ATTRS = {"cases_fallback", "fallback_reasons"}


@pytest.mark.parametrize(
    "text",
    [TEXT, ON_SEABED, ON_SLOPE, ON_SEABED_B, LENGTHS, NODES, CURRENT, FORCE, FRICTION]
    + [ANALYTIC, DISCRETE, SHOOTING, POLYNOMIAL],
    ids=[
        "free",
        "on-seabed",
        "on-sloped-seabed-friction",
        "anchored-at-b",
        "segment-length",
        "node-count",
        "current-speed-heading-drag",
        "force-end",
        "seabed-friction-depth",
        "method-analytic",
        "method-discrete",
        "method-shooting",
        "nonlinear-law-breaks",
    ],
)
def test_array_path_writes_the_case_by_case_dataset_bit_for_bit(tmp_path: Path, text: str) -> None:
    fast, slow = _both(tmp_path, text)
    if text == TEXT:
        assert int((slow["status"] == 0).sum()) == 42  # slack to stretched, all solved
    elif text in (ON_SEABED, ON_SLOPE, ON_SEABED_B, FRICTION):
        assert float(slow["laid_length"].max()) > 0.0  # the seabed path did run
    # a sweep that does not solve is no test of equality: most cases keep their results
    kept = np.isin(slow["status"].values, KEPT_STATUSES)
    assert int(kept.sum()) >= kept.size // 2
    if text in (LENGTHS, NODES):  # per case arc lengths: s is the node index
        assert "arc_length" in fast.data_vars and fast["s"].attrs["long_name"] == "node index"
    if text == POLYNOMIAL:  # the stretched spans broke: kept, counted apart from failures
        assert fast.attrs["cases_broken"] == int((fast["status"] == 10).sum()) > 0
    if text in (ANALYTIC, DISCRETE, SHOOTING):  # no batch kernel: every case counted, with why
        method = {ANALYTIC: "analytic", DISCRETE: "discrete", SHOOTING: "shooting"}[text]
        assert fast.attrs["cases_fallback"] == 4
        assert fast.attrs["fallback_reasons"] == f"4 x method {method!r} has no batch kernel"
    if text == NODES:  # the 11-node cases are padded with NaN after their last node
        assert bool(np.isnan(fast["x"].sel(nodes=11).isel(s=slice(11, None))).all())
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
    # any numeric key of a static study is a grid; the array route for end positions,
    # stiffnesses, the numbers of the line and the seabed, the static settings, with any
    # static method; not for gravity, nor a line with a non-linear law
    text = TEXT.replace("ends.a.position.2: [-10.0, -20.0]", "environment.gravity: [9.8, 9.81]")
    grid = expand_grid(parse_study_text(text, "gr.yaml"))
    assert grid.chunked and not grid.arrays
    text = TEXT.replace(
        "axial_stiffness: 2.0e8}", "axial: {law: polynomial, coefficients: [2.0e8, 1.0e9]}}"
    )
    grid = expand_grid(parse_study_text(text, "gr.yaml"))
    assert grid.chunked and not grid.arrays
    text = TEXT.replace("ends.a.position.2: [-10.0, -20.0]", "analysis.static.nodes: [21, 31]")
    assert expand_grid(parse_study_text(text, "gr.yaml")).arrays
    text = TEXT.replace("method: catenary", "method: analytic")
    assert expand_grid(parse_study_text(text, "gr.yaml")).arrays
    # not in chunks of rows (their cases through the per-case evaluators): a dynamic
    # analysis, a value that is not a number
    dynamic = TEXT.replace(
        "static: {method: catenary, nodes: 21}",
        "static: {method: catenary, nodes: 21}\n  modal: {modes: 2}",
    )
    assert not expand_grid(parse_study_text(dynamic, "gr.yaml")).chunked
    text = TEXT.replace(
        "ends.a.position.2: [-10.0, -20.0]", "analysis.static.method: [catenary, shooting]"
    )
    grid = expand_grid(parse_study_text(text, "gr.yaml"))
    assert not grid.chunked and grid.whole == ()  # the methods copied into the template


def test_faulty_swept_values_are_reported_as_before() -> None:
    """A bad swept value or combination is reported at its line with the sweep case,
    exactly as the case-by-case validation reported it."""
    bad_value = TEXT.replace("[1.0e5, 1.0e6, 6.283e7]", "[1.0e5, -1.0e6, 6.283e7]")
    src = parse_study_text(bad_value, "gr.yaml")
    with pytest.raises(StudyError) as exc:
        expand_grid(src)
    assert "line.segments.0.axial_stiffness" in str(exc.value)
    # each value valid on its own, but end A below the seabed only with another axis
    below = TEXT.replace("ends.a.position.2: [-10.0, -20.0]", "ends.a.position.2: [-10.0, -60.0]")
    with pytest.raises(StudyError, match="below the seabed"):
        expand_grid(parse_study_text(below, "gr.yaml"))
    seabed = below.replace("depth: 50.0", "depth: 70.0")
    assert expand_grid(parse_study_text(seabed, "gr.yaml")).arrays
    # a combination no compiled kernel takes: a swept depth with a swept end height
    # (each valid alone; depth 30 m with end A at -40 m is not): checked by the models'
    # own validators on each case's copied study, reported by the case path as before
    depth = TEXT.replace(STIFF, "environment.depth: [30.0, 70.0]").replace(
        "[-10.0, -20.0]", "[-10.0, -40.0]"
    )
    src = parse_study_text(depth, "gr.yaml")
    with pytest.raises(StudyError) as exc:
        expand_grid(src)
    text = str(exc.value)
    assert "lies below the seabed" in text and "of 28 sweep cases, first" in text, text
    assert expand_grid(parse_study_text(depth.replace("-40.0", "-25.0"), "gr.yaml")).chunked
    # a segment length that puts an attachment beyond the end of the line
    beyond = LENGTHS.replace(
        "ends:\n", "  attachments:\n    - {s: 95.0, force: [0.0, 0.0, -100.0]}\nends:\n"
    ).replace("[40.0, 47.5]", "[30.0, 47.5]")
    src = parse_study_text(beyond, "gr.yaml")
    with pytest.raises(StudyError) as exc:
        expand_grid(src)
    assert "beyond the end of the line" in str(exc.value)


def test_streamed_result_opens_lazily_and_chunks_are_cached(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    from cablestudy.analyses import static_grid as grid_module

    monkeypatch.setattr(grid_runner, "GRID_CHUNK_CASES", 12)  # two rows of 6 cases a chunk
    monkeypatch.setattr(grid_runner, "IN_MEMORY_BYTES", 0)  # streamed, as a large study is
    src = parse_study_text(TEXT, "gr.yaml")
    grid = expand_grid(src)
    first = run_study(src, grid, tmp_path, scheduler="synchronous", progress=False)
    files = sorted((tmp_path / ".cache" / "gr").glob("grid-*.npz"))
    assert len(files) == 4  # rows 0-1, 2-3, 4-5, 6
    lazy = xr.open_dataset(first.path, chunks={})
    assert lazy["x"].chunks is not None  # dask-backed: read on demand
    # written with explicit netCDF chunks of whole blocks of cases (two spans)
    assert lazy["x"].encoding["chunksizes"] == (2, 3, 2, 21)
    ref = xr.load_dataset(first.path)
    # the streamed file is the one the in-memory assembly writes
    monkeypatch.setattr(grid_runner, "IN_MEMORY_BYTES", 1 << 30)
    held = run_study(
        src, grid, tmp_path / "held", scheduler="synchronous", use_cache=False, progress=False
    )
    xr.testing.assert_identical(
        xr.load_dataset(held.path).drop_vars("wall_time"),
        ref.drop_vars("wall_time").assign_attrs(history=held_history(held.path)),
    )
    monkeypatch.setattr(grid_runner, "IN_MEMORY_BYTES", 0)
    calls: list[int] = []
    real = evaluate_grid_chunk

    def counted(g, lo, hi):  # noqa: ANN001, ANN202
        calls.append(lo)
        return real(g, lo, hi)

    monkeypatch.setattr(grid_module, "evaluate_grid_chunk", counted)
    raw = bytearray(files[1].read_bytes())
    raw[len(raw) // 3] ^= 0x10
    files[1].write_bytes(bytes(raw))
    capsys.readouterr()
    second = run_study(src, grid, tmp_path, scheduler="synchronous", progress=False)
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


@pytest.mark.parametrize("parallel", ["processes", "threads"])
def test_array_chunks_on_workers_give_the_serial_result(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, parallel: str
) -> None:
    """Rows of an array grid run on the one execution loop of every study: on worker
    processes or threads, the serial result."""
    monkeypatch.setattr(grid_runner, "GRID_CHUNK_CASES", 12)
    src = parse_study_text(TEXT, "gr.yaml")
    grid = expand_grid(src)
    par = run_study(
        src,
        grid,
        tmp_path / "p",
        scheduler=parallel,
        workers=2,
        use_cache=False,
        progress=False,
    )
    ser = run_study(
        src, grid, tmp_path / "s", scheduler="synchronous", use_cache=False, progress=False
    )
    assert par.scheduler == parallel and ser.scheduler == "synchronous"
    a, b = xr.load_dataset(par.path), xr.load_dataset(ser.path)
    xr.testing.assert_identical(
        a.drop_vars("wall_time"), b.drop_vars("wall_time").assign_attrs(history=a.attrs["history"])
    )
    assert not list((tmp_path / "p").glob(".gr-chunks-*"))  # the scratch folder is gone


def test_a_local_cluster_that_does_not_start_leaves_the_run_to_threads(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    """Worker processes that do not come up within the start time-out (here: at once)
    do not hold or fail the run: it goes on threads, says so, and gives the serial
    result."""
    from cablestudy.run import scheduler as sched

    def no_cluster(scheduler: str, workers: int) -> None:
        raise TimeoutError("the nanny gave up after 60 s")

    monkeypatch.setattr(sched, "_local_cluster", no_cluster)
    monkeypatch.setattr(grid_runner, "GRID_CHUNK_CASES", 12)
    src = parse_study_text(TEXT, "gr.yaml")
    grid = expand_grid(src)
    par = run_study(
        src, grid, tmp_path / "p", scheduler="processes", workers=2, use_cache=False, progress=False
    )
    ser = run_study(
        src, grid, tmp_path / "s", scheduler="synchronous", use_cache=False, progress=False
    )
    err = capsys.readouterr().err
    assert "did not start (TimeoutError: the nanny gave up after 60 s)" in err
    assert "on 2 threads instead" in err
    a, b = xr.load_dataset(par.path), xr.load_dataset(ser.path)
    np.testing.assert_array_equal(a["tension_a"].values, b["tension_a"].values)


def test_a_cluster_that_does_not_stop_is_given_up_after_the_results() -> None:
    """A stop that times out (the results are all in by then) kills the cluster's worker
    processes left (named by distributed) and says so, instead of failing or holding
    the run; another child of the process is left alone."""
    import multiprocessing

    from cablestudy.run import scheduler as sched

    class Stuck:
        def __init__(self) -> None:
            self.closed: list[float | None] = []

        def close(self, timeout: float | None = None) -> None:
            self.closed.append(timeout)
            raise TimeoutError("still closing")

    fork = multiprocessing.get_context("fork")
    child = fork.Process(target=time.sleep, args=(60,), name="Dask Worker process (from Nanny)")
    other = fork.Process(target=time.sleep, args=(60,), name="not a worker")
    child.start()
    other.start()
    try:
        stuck = Stuck()
        sched._close(stuck, stuck)  # no exception
        child.join(10)
        assert stuck.closed == [sched.CLUSTER_TIMEOUT]  # the client's close raised first
        assert child.exitcode is not None and child.exitcode < 0  # killed
        assert other.is_alive()
    finally:
        other.kill()
        other.join(10)


def test_an_extended_first_axis_reuses_the_cached_chunks(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from cablestudy.analyses import static_grid as grid_module

    monkeypatch.setattr(grid_runner, "GRID_CHUNK_CASES", 12)  # two spans a chunk
    spans = "ends.b.position.0: {start: 60.0, stop: 100.5, num: 7, name: span}"
    short = TEXT.replace(spans, "ends.b.position.0: {values: [60.0, 70.0, 80.0, 90.0], name: span}")
    longer = short.replace("[60.0, 70.0, 80.0, 90.0]", "[60.0, 70.0, 80.0, 90.0, 95.0, 100.0]")
    src = parse_study_text(short, "gr.yaml")
    run_study(src, expand_grid(src), tmp_path, scheduler="synchronous", progress=False)
    calls: list[int] = []
    real = evaluate_grid_chunk

    def counted(g, lo, hi):  # noqa: ANN001, ANN202
        calls.append(lo)
        return real(g, lo, hi)

    monkeypatch.setattr(grid_module, "evaluate_grid_chunk", counted)
    src2 = parse_study_text(longer, "gr.yaml")
    again = run_study(src2, expand_grid(src2), tmp_path, scheduler="synchronous", progress=False)
    assert calls == [4] and again.n_reused == 24 and again.n_computed == 12
    # a changed value of another axis changes every chunk
    other = longer.replace("[-10.0, -20.0]", "[-10.0, -25.0]")
    src3 = parse_study_text(other, "gr.yaml")
    calls.clear()
    run_study(src3, expand_grid(src3), tmp_path, scheduler="synchronous", progress=False)
    assert calls == [0, 2, 4]


def held_history(path: Path) -> str:
    with xr.open_dataset(path) as ds:
        return str(ds.attrs["history"])


def test_the_default_method_takes_the_array_path_as_the_written_one(tmp_path: Path) -> None:
    """Which path a study takes is decided from the validated study, defaults included:
    leaving out ``method: catenary`` (the default) must not send a sweep case by case."""
    from cablestudy.cli import _load
    from cablestudy.study.grid import CaseGrid

    written, left_out = tmp_path / "written.yaml", tmp_path / "left_out.yaml"
    written.write_text(TEXT)
    left_out.write_text(TEXT.replace("method: catenary, ", ""))
    (_, _, a), (_, _, b) = _load(str(written)), _load(str(left_out))
    assert isinstance(a, CaseGrid) and isinstance(b, CaseGrid)
    assert a.key == b.key  # the same template with its defaults: the same cases, one cache


def test_with_and_without_method_and_a_key_no_kernel_takes_share_one_path(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """The method written, left out, and a swept key some cases of which no compiled
    kernel takes (a current with drag on a line anchored on the seabed, near taut): all
    three are array grids run by the same runner (the current's chunk through
    solve_batch), and the cases the batch kernels did not settle are counted with their
    reason, in the dataset and the summary."""
    from cablestudy import cli
    from cablestudy.study.grid import CaseGrid

    left_out = TEXT.replace("method: catenary, ", "")
    # end A on the seabed (a line hanging free over it is the drag kernel's)
    anchored = CURRENT.replace("position: [0.0, 0.0, -10.0]", "position: [0.0, 0.0, -50.0]")
    assert anchored != CURRENT
    found = {}
    for label, text in (("written", TEXT), ("left-out", left_out), ("current", anchored)):
        path = tmp_path / f"{label}.yaml"
        path.write_text(text)
        _, _, grid = cli._load(str(path))
        assert isinstance(grid, CaseGrid), label
        assert cli.main(["run", str(path), "--out", str(tmp_path / label)]) == 0
        report = capsys.readouterr().out
        with xr.open_dataset(tmp_path / label / "gr.nc") as ds:
            found[label] = (grid, dict(ds.attrs), report, int((ds["status"] == 0).sum()))
    written, left, current = found["written"], found["left-out"], found["current"]
    # a current, too, runs as arrays (its chunk through solve_batch, the drag iteration
    # per case compiled, anchored on the seabed too)
    assert written[0].arrays and left[0].arrays and current[0].arrays
    # the same template with its defaults: the same kernel, the same cases and counts
    assert written[0].key == left[0].key
    assert written[1]["cases_fallback"] == left[1]["cases_fallback"]
    # in air-free still water every case between separated ends is the kernel's
    assert written[3] == 42
    # with a current (speeds 0.5 and 1.0 of [0, 0.5, 1.0]) the anchored drag kernel takes
    # the slack span (80 m); at 95 m the 100 m line is near taut and may leave its anchor
    # upwards, so its four current cases (2 speeds x 2 headings) go to the general
    # solver's free-hanging path, counted with that reason; still water is the contact
    # kernel's
    attrs, report = current[1], current[2]
    n = 4
    assert current[3] == current[0].size
    assert attrs["cases_fallback"] == n
    assert attrs["fallback_reasons"] == (
        f"{n} x anchored on the seabed, it may hang free of it (the free-hanging path)"
    )
    assert f"{n} cases solved by the general solver (no batch kernel took them)" in report
    assert "cases solved by the general solver" not in written[2]


@pytest.mark.parametrize("text", [LENGTHS, NODES, CURRENT, FORCE, FRICTION, ANALYTIC])
def test_chunk_keys_change_with_every_swept_value(text: str) -> None:
    """A chunk's cache key is a content hash of its cases: changing any one swept value
    of any key (the last value of each axis) changes the key of the chunk holding it."""
    src = parse_study_text(text, "gr.yaml")
    grid = expand_grid(src)
    assert grid is not None
    n0 = grid.shape[0]
    base = grid.chunk_key(0, n0)
    for path, (axis, vals) in grid.swept.items():
        other = {**grid.swept, path: (axis, np.concatenate([vals[:-1], [vals[-1] * 1.001]]))}
        changed = CaseGrid(grid.template, grid.axes, other, grid.key, grid.validated, grid.arrays)
        assert changed.chunk_key(0, n0) != base, path
    assert expand_grid(src).chunk_key(0, n0) == base  # and it is reproducible


@pytest.mark.parametrize("text", [LENGTHS, NODES, CURRENT, FORCE, FRICTION])
def test_a_copied_case_study_is_the_validated_one(text: str) -> None:
    """Each case's study built by copying the template (CaseGrid.study_at) is the study
    the full validation of the case's YAML gives: every field, and what the validators
    derive (a line's total length), but the sweep table itself."""
    from cablestudy.study.cases import _copy_tree, _set_path
    from cablestudy.study.loader import validate_data

    src = parse_study_text(text, "gr.yaml")
    grid = expand_grid(src)
    assert len(grid.cases()) == grid.size
    for case in grid.cases():
        data = _copy_tree({k: v for k, v in src.data.items() if k != "sweep"})
        for axis, a in enumerate(grid.axes):
            _set_path(data, a.paths[0], a.values[0][case.index[axis]])
        full = validate_data(data, src)
        copied = grid.study_at(case.index)
        # the template keeps its sweep table, which no case's result reads
        assert copied.model_dump(exclude={"sweep"}) == full.model_dump(exclude={"sweep"})
        assert copied.line.length == full.line.length


def test_a_grid_of_one_case_is_the_case_path_and_its_kernel_counts(tmp_path: Path) -> None:
    """One case (a one-value sweep of a key the compiled arrays do not take): a chunk of
    one, the same record as the case path; the catenary solver takes the compiled kernel
    for it alone, so it is no fallback."""
    one = (
        LENGTHS.replace(SPANS, "ends.b.position.0: [92.5]")
        .replace(STIFF, "line.segments.0.axial_stiffness: [6.283e7]")
        .replace("[40.0, 47.5]", "[45.0]")
    )
    fast, slow = _both(tmp_path, one)
    assert fast["status"].size == 1 and int(fast["status"].item()) == 0
    for name in slow.data_vars:
        if name != "wall_time" and slow[name].dtype.kind == "f":
            assert fast[name].values.tobytes() == slow[name].values.tobytes(), name
    assert fast.attrs["cases_fallback"] == 0 and fast.attrs["fallback_reasons"] == ""


def test_lines_anchored_on_the_seabed_are_the_contact_kernels_one_by_one(tmp_path: Path) -> None:
    """A friction x depth sweep of a line anchored on the seabed: the catenary solver takes
    the compiled contact kernel per case; only the cases it did not settle (slack on
    the seabed, say) count as solved by the general solver, with the kernel's reason."""
    from cablestudy.statics.batch_kernels import NOT_SETTLED, ON_SEABED

    fast, _ = _both(tmp_path, FRICTION)
    laid = fast["laid_length"].values > 0.0
    assert laid.sum() >= 12  # the contact kernel's cases: resting on the seabed
    assert fast.attrs["cases_fallback"] < fast["status"].size
    counted = [part.split(" x ", 1) for part in fast.attrs["fallback_reasons"].split("; ")]
    assert {why for _, why in counted} <= {NOT_SETTLED, ON_SEABED}, counted
    assert sum(int(k) for k, _ in counted) == fast.attrs["cases_fallback"]
