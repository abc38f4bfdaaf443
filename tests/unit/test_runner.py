"""Runner: chunking, failure capture, the case cache (reuse, resume after an interrupt),
failure summary and progress bar. All on the synchronous scheduler (the distributed one
is exercised in tests/integration)."""

from __future__ import annotations

import time
from collections import OrderedDict
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cablestudy.analyses import static as static_analysis
from cablestudy.run import scheduler
from cablestudy.run.cache import GridChunkStore
from cablestudy.run.progress import (
    WARNING_EXAMPLES,
    Progress,
    RunSummary,
    group_failures,
    group_warnings,
)
from cablestudy.run.runner import run_study
from cablestudy.run.scheduler import (
    MAX_CHUNK_CASES,
    STRIPES,
    TARGET_TASK_SECONDS,
    make_chunks,
    probe_cost,
    run_chunk,
)
from cablestudy.statics import STATIC_SOLVERS, STATUS_OK
from cablestudy.study import parse_study_text
from cablestudy.study.cases import Case
from cablestudy.study.grid import expand_grid

TEXT = """\
name: rn
environment: {fluid: air}
line:
  segments:
    - {length: 100.0, diameter: 0.02, mass_per_length: 2.466, axial_stiffness: 6.283e7}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [92.5, 0.0, -8.6]}
analysis:
  static: {method: analytic, nodes: 5}
sweep:
  ends.b.position.0: {start: 60.0, stop: 100.0, num: 9, name: span}
  line.segments.0.axial_stiffness: [1.0e6, 1.0e7, 6.283e7]
"""


def _expand(text: str = TEXT):  # noqa: ANN202
    src = parse_study_text(text, "rn.yaml")
    # the records path (chunks of case records on the probing scheduler, the per-case
    # cache), which runs every grid that is not chunked, for this static sweep too
    grid = replace(expand_grid(src), chunked=False)
    return src, grid, grid.cases()


_RUN_CHUNK = run_chunk


@pytest.fixture(autouse=True)
def _fresh_static_cache(monkeypatch: pytest.MonkeyPatch) -> None:
    # evaluate_case memoises static solutions per process: start each test empty
    monkeypatch.setattr(static_analysis, "_STATIC_CACHE", OrderedDict())


def _count_evaluations(monkeypatch: pytest.MonkeyPatch, interrupt_after: int | None = None):  # noqa: ANN202
    """Wrap runner.run_chunk: count evaluated cases; raise KeyboardInterrupt (as Ctrl-C
    would) when chunk number ``interrupt_after`` + 1 starts."""
    counter = {"cases": 0, "chunks": 0}
    real = _RUN_CHUNK

    def counted(chunk: list[Case]):  # noqa: ANN202
        if interrupt_after is not None and counter["chunks"] >= interrupt_after:
            raise KeyboardInterrupt
        counter["chunks"] += 1
        counter["cases"] += len(chunk)
        return real(chunk)

    monkeypatch.setattr(scheduler, "run_chunk", counted)
    return counter


def _key(c: Case) -> tuple[str, tuple[int, ...]]:
    return (c.static_hash, c.index)


def test_chunks_cover_every_case_once_and_batch_cheap_cases() -> None:
    _, _, cases = _expand()
    chunks = make_chunks(cases, workers=2)
    flat = [c.hash for ch in chunks for c in ch]
    assert sorted(flat) == sorted(c.hash for c in cases)
    assert len(chunks) == 8  # 4 chunks per worker for load balance
    # thousands of cases: at most 200 per chunk, far fewer tasks than cases
    many = [Case((i,), {}, cases[0].study, f"h{i}", f"s{i % 7}") for i in range(5000)]
    big = make_chunks(many, workers=2)
    assert len(big) == 25 and max(len(c) for c in big) == 200
    # a chunk is STRIPES runs of adjacent cases (cases sharing a static problem stay
    # together, so its solution is reused): a run spans at most two static problems
    for ch in big:
        runs = [c.static_hash for c in ch]
        assert len(set(runs)) <= 2 * STRIPES
        assert sum(a != b for a, b in zip(runs, runs[1:], strict=False)) <= 2 * STRIPES
    # submitted from both ends of the sweep inwards: the first and last cases start first
    assert big[0][0] is sorted(many, key=_key)[0]
    assert big[1][-1] is sorted(many, key=_key)[-1]


def test_a_solver_exception_is_a_failed_case_and_the_study_finishes(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    real = STATIC_SOLVERS["analytic"]

    class Flaky:
        name = "analytic"

        def unsupported(self, problem):  # noqa: ANN001, ANN201
            return real.unsupported(problem)

        def solve(self, problem, *, deadline=None):  # noqa: ANN001, ANN201
            EA = float(problem.line.axial_stiffness[0])
            if EA == 1.0e6:
                raise ZeroDivisionError("float division by zero")
            res = real.solve(problem, deadline=deadline)
            if EA == 1.0e7 and problem.end_b.position[0] == 60.0:
                res.tension[2] = np.nan  # NaN with status 0: must become a failure
            return res

    monkeypatch.setitem(STATIC_SOLVERS, "analytic", Flaky())
    src, grid, cases = _expand()
    summary = run_study(src, grid, tmp_path, scheduler="synchronous", progress=False)
    ds = xr.load_dataset(summary.path)
    failed = ds["status"].sel(axial_stiffness=1.0e6)
    assert np.all(failed != STATUS_OK)
    assert all(
        "ZeroDivisionError: float division by zero" in str(m)
        for m in ds["message"].sel(axial_stiffness=1.0e6).values
    )
    assert np.all(np.isnan(ds["tension"].sel(axial_stiffness=1.0e6)))
    nan_case = ds.sel(axial_stiffness=1.0e7, span=60.0)
    assert int(nan_case["status"]) != STATUS_OK and "non-finite" in str(nan_case["message"].item())
    assert np.all(np.isnan(nan_case["tension"]))
    ok = ds["status"].sel(axial_stiffness=6.283e7)
    assert np.all(ok == STATUS_OK)
    assert np.all(np.isfinite(ds["tension"].sel(axial_stiffness=6.283e7)))
    assert summary.n_failed == 10 and ds.attrs["cases_failed"] == 10
    report = summary.report()
    assert "failures by message:" in report
    assert "     9 x ZeroDivisionError: float division by zero" in report
    assert "     1 x " in report and "non-finite" in report


def test_rerun_reuses_every_finished_case(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    src, grid, cases = _expand()
    first = run_study(src, grid, tmp_path, scheduler="synchronous", progress=False)
    assert (first.n_computed, first.n_reused) == (27, 0)
    counter = _count_evaluations(monkeypatch)
    second = run_study(src, grid, tmp_path, scheduler="synchronous", progress=False)
    assert counter["cases"] == 0 and (second.n_computed, second.n_reused) == (0, 27)
    # an added sweep value computes only the new cases
    src3, grid3, cases3 = _expand(
        TEXT.replace("[1.0e6, 1.0e7, 6.283e7]", "[1.0e6, 1.0e7, 6.283e7, 1.0e8]")
    )
    third = run_study(src3, grid3, tmp_path, scheduler="synchronous", progress=False)
    assert counter["cases"] == 9 and third.n_reused == 27


def test_interrupted_study_resumes_without_losing_or_redoing_work(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    src, grid, cases = _expand()
    reference = run_study(
        src, grid, tmp_path / "ref", scheduler="synchronous", use_cache=False, progress=False
    )
    out = tmp_path / "run"
    counter = _count_evaluations(monkeypatch, interrupt_after=3)
    with pytest.raises(KeyboardInterrupt):
        run_study(src, grid, out, scheduler="synchronous", progress=False)
    done = counter["cases"]
    assert 0 < done < len(cases)
    assert not (out / "rn.nc").exists()  # no partial result file
    counter = _count_evaluations(monkeypatch)
    summary = run_study(src, grid, out, scheduler="synchronous", progress=False)
    assert counter["cases"] == len(cases) - done  # finished cases were not recomputed
    assert summary.n_reused == done
    got, ref = xr.load_dataset(summary.path), xr.load_dataset(reference.path)
    skip = ["wall_time", "message"]
    xr.testing.assert_identical(
        got.drop_vars(skip), ref.drop_vars(skip).assign_attrs(history=got.attrs["history"])
    )


def test_cache_survives_a_corrupt_file_and_skips_transient_failures(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from cablestudy.analyses.grid_chunk import records_chunk
    from cablestudy.analyses.variables import CaseRecord
    from cablestudy.run.grid_runner import _CasePlan

    store = GridChunkStore(tmp_path)
    ok = CaseRecord(hash="a", index=(0,), status=0, message="", wall_time=0.1)
    slow = CaseRecord(
        hash="b", index=(1,), status=3, message="time limit reached after 3", wall_time=0.1
    )
    plan = _CasePlan.__new__(_CasePlan)  # its cache writing alone
    plan.store = store
    chunk = records_chunk([ok, slow])
    plan.span(chunk)
    written = plan.write(chunk)
    garbage = tmp_path / ("grid-" + "0" * 32 + "-" + "0" * 64 + ".npz")
    garbage.write_bytes(b"not an archive")
    found, files = store.cases({"a", "b"})
    # the time-limited case will be retried: not kept
    assert [c.hashes.tolist() for c in found] == [["a"]] and files == {written}
    assert not garbage.exists()
    assert str(garbage) in capsys.readouterr().err
    store.cases({"a", "b"})
    assert capsys.readouterr().err == ""  # reported once: the bad file is gone


def test_cache_chunks_round_trip_exactly(tmp_path: Path) -> None:
    """Every kind of value a case produces comes back from the cache with its dtype, shape
    and bits, in the one chunk form (a shorter value padded, a failed analysis's output
    the fill)."""
    from cablestudy.analyses.grid_chunk import records_chunk
    from cablestudy.analyses.variables import CaseRecord

    rng = np.random.default_rng(1)
    recs = [
        CaseRecord(
            hash="h0",
            index=(0, 2),
            status=0,
            message="",
            wall_time=0.125,
            data={
                "x": rng.standard_normal(7),
                "force_a": np.array([1.0, -0.0, np.nan]),
                "tension_a": np.float64(1.0 / 3.0),
                "static_iterations": 4.0,
                "dynamic_method": "frequency",
                "mode_shape": rng.standard_normal((2, 7, 3)),
            },
        ),
        CaseRecord(
            hash="h1",
            index=(1, 0),
            status=0,
            message="did not converge: résidu 1e-3",
            wall_time=float("nan"),
            data={
                "x": rng.standard_normal(5),
                "dynamic_method": np.array("time"),
                "static_status": np.int64(0),
                "dynamic_status": np.int64(4),
            },
        ),
    ]
    store = GridChunkStore(tmp_path)
    chunk = records_chunk(recs)
    chunk.key = "f" * 64
    back = store.chunk(store.write(chunk))
    assert back.hashes.tolist() == ["h0", "h1"] and back.status.tolist() == [0, 0]
    assert back.message.tolist() == ["", "did not converge: résidu 1e-3"]
    assert np.array_equal(back.wall_time, [0.125, np.nan], equal_nan=True)
    assert set(back.data) == set(chunk.data)
    for k, v in chunk.data.items():
        assert back.data[k].dtype == v.dtype and back.data[k].shape == v.shape, k
        if v.dtype.kind == "f":
            assert back.data[k].tobytes() == v.tobytes(), k  # bit for bit (-0.0, NaN)
        else:
            assert np.array_equal(back.data[k], v), k
    x = back.data["x"]
    assert x[0].tobytes() == recs[0].data["x"].tobytes()
    assert x[1, :5].tobytes() == recs[1].data["x"].tobytes() and np.isnan(x[1, 5:]).all()
    assert back.data["dynamic_method"].tolist() == ["frequency", ""]  # its analysis failed
    assert np.isnan(back.data["mode_shape"][1]).all()


def test_cache_refuses_to_store_python_objects(tmp_path: Path) -> None:
    from cablestudy.analyses.grid_chunk import GridChunk
    from cablestudy.run.cache import CacheFormatError

    chunk = GridChunk(
        0,
        1,
        "f" * 64,
        np.zeros(1, dtype=np.int64),
        np.array([""]),
        np.zeros(1),
        {"x": np.array([object()], dtype=object)},
    )
    with pytest.raises(CacheFormatError, match="'x' holds Python objects"):
        GridChunkStore(tmp_path).write(chunk)


def test_cached_rerun_is_bit_for_bit_the_uncached_run(tmp_path: Path) -> None:
    src, grid, cases = _expand()
    plain = run_study(
        src,
        grid,
        tmp_path / "plain",
        scheduler="synchronous",
        use_cache=False,
        progress=False,
    )
    first = run_study(src, grid, tmp_path / "c", scheduler="synchronous", progress=False)
    second = run_study(src, grid, tmp_path / "c", scheduler="synchronous", progress=False)
    assert second.n_reused == len(cases)
    ref, a, b = (xr.load_dataset(p.path) for p in (plain, first, second))
    # the cached rerun reproduces the run that filled the cache, wall times included
    xr.testing.assert_identical(b.assign_attrs(history=a.attrs["history"]), a)
    for name in a.data_vars:
        if a[name].dtype.kind == "f":
            assert a[name].values.tobytes() == b[name].values.tobytes(), name
    # ... and agrees bit for bit with the uncached run (wall times aside)
    for name in ref.data_vars:
        if name != "wall_time":
            assert ref[name].values.tobytes() == b[name].values.tobytes(), name


def test_chunk_files_of_earlier_versions_are_removed_when_the_cache_is_tidied(
    tmp_path: Path,
) -> None:
    """The ``chunk-*.npz`` files of earlier versions are never read; a run that may tidy
    the cache (no other run of the study writing) removes them, and the study's own
    chunk files stay and are reused, on either plan (cases by hash, rows by key)."""
    for chunked in (False, True):
        src, grid, cases = _expand()
        grid = replace(grid, chunked=chunked)
        out = tmp_path / str(chunked)
        run_study(src, grid, out, scheduler="synchronous", progress=False)
        cache = out / ".cache" / "rn"
        ours = sorted(cache.glob("grid-*.npz"))
        old = cache / "chunk-0123456789abcdef.npz"
        old.write_bytes(b"an earlier version's chunk")
        again = run_study(src, grid, out, scheduler="synchronous", progress=False)
        assert again.n_reused == len(cases) and again.n_computed == 0
        assert not old.exists() and sorted(cache.glob("grid-*.npz")) == ours


@pytest.mark.parametrize("damage", ["truncate", "garble"])
def test_damaged_cache_chunk_is_reported_once_and_recomputed(
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    capsys: pytest.CaptureFixture[str],
    damage: str,
) -> None:
    src, grid, cases = _expand()
    first = run_study(src, grid, tmp_path, scheduler="synchronous", progress=False)
    ref = xr.load_dataset(first.path)
    (chunk,) = (tmp_path / ".cache" / "rn").glob("grid-*.npz")  # compacted to one
    raw = bytearray(chunk.read_bytes())
    if damage == "truncate":
        chunk.write_bytes(bytes(raw[: len(raw) // 2]))
    else:
        raw[len(raw) // 2] ^= 0x01  # one bit
        chunk.write_bytes(bytes(raw))
    capsys.readouterr()
    counter = _count_evaluations(monkeypatch)
    second = run_study(src, grid, tmp_path, scheduler="synchronous", progress=False)
    err = capsys.readouterr().err
    assert err.count("warning: cache file") == 1 and str(chunk) in err and "recomputed" in err
    assert counter["cases"] == len(cases) and second.n_reused == 0
    got = xr.load_dataset(second.path)
    for name in ref.data_vars:
        if name != "wall_time":
            assert ref[name].values.tobytes() == got[name].values.tobytes(), name
    third = run_study(src, grid, tmp_path, scheduler="synchronous", progress=False)
    assert third.n_reused == len(cases) and capsys.readouterr().err == ""


class _Trap:
    """Unpickling this writes a marker file: proof that a pickle was loaded."""

    def __init__(self, marker: str) -> None:
        self.marker = marker

    def __reduce__(self):  # noqa: ANN204
        return (Path.write_text, (Path(self.marker), "unpickled"))


def test_a_pickle_in_the_cache_is_never_unpickled(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    import hashlib
    import pickle

    marker = tmp_path / "marker"
    payload = pickle.dumps([_Trap(str(marker))])
    cache_dir = tmp_path / "cache"
    cache_dir.mkdir()
    # as an old-style pickle chunk, and disguised as a data chunk with a valid hash name
    (cache_dir / "chunk-0123456789abcdef01234567.pkl").write_bytes(payload)
    key = "0" * 32
    disguised = cache_dir / f"grid-{key}-{hashlib.sha256(payload).hexdigest()}.npz"
    disguised.write_bytes(payload)
    # a pickled object array inside a real .npz archive, also with a valid hash name
    import io

    buf = io.BytesIO()
    np.savez(buf, format=np.array("cablestudy-grid-chunk-1"), v_hash=np.array([_Trap(str(marker))]))
    inner = cache_dir / f"grid-{key}-{hashlib.sha256(buf.getvalue()).hexdigest()}.npz"
    inner.write_bytes(buf.getvalue())
    found, files = GridChunkStore(cache_dir).cases({"a"})
    assert not marker.exists()
    assert found == [] and files == set()
    err = capsys.readouterr().err
    assert str(disguised) in err and str(inner) in err
    assert not disguised.exists() and not inner.exists()  # removed: recomputed


def test_failures_grouped_by_message_with_numbers_masked() -> None:
    failures = {
        "did not converge (residual 1.2e-05)": 3,
        "did not converge (residual 4e-3)": 2,
        "singular Jacobian": 1,
    }
    groups = group_failures(failures)
    assert list(groups.values())[0] == (5, "did not converge (residual 1.2e-05)")
    report = RunSummary(Path("x.nc"), 10, 0, 10, 6, 1.0, failures).report()
    assert "     5 x did not converge (residual #)  (e.g." in report
    assert "     1 x singular Jacobian" in report


def test_warnings_grouped_by_kind_with_examples_of_their_cases() -> None:
    """A case's warning text holds one warning per kind ('; '-separated): each counts once
    under its kind, with at most three distinct examples, each after its case."""
    slack = "slack: the dynamic tension at the excited end falls to -3 N (at or below zero)"
    unsettled = "unsettled: no steady state after 80 periods (analysis.dynamic.max_periods 80)"
    warnings = {f"{slack}; {unsettled}": 2, slack: 5, "strain: largest strain 0.2 above": 1}
    cases = {f"{slack}; {unsettled}": "amplitude=1", slack: "amplitude=0.5"}
    groups = group_warnings(warnings, cases)
    assert list(groups) == ["slack", "unsettled", "strain"]
    assert groups["slack"] == (7, [f"amplitude=1: {slack}", f"amplitude=0.5: {slack}"])
    assert groups["unsettled"] == (2, [f"amplitude=1: {unsettled}"])
    assert groups["strain"] == (1, ["strain: largest strain 0.2 above"])
    many = {f"slack: falls to {-i} N": 1 for i in range(6)}
    assert len(group_warnings(many)["slack"][1]) == WARNING_EXAMPLES
    report = RunSummary(
        Path("x.nc"), 8, 0, 8, 0, 1.0, n_warned=8, warnings=warnings, warned_cases=cases
    ).report()
    assert "8 cases (8 computed, 0 reused from cache), 0 failed, 8 with warnings" in report
    assert "warnings by kind (the cases keep status 0):\n       7 x slack, e.g.:\n" in report
    assert f"\n           amplitude=0.5: {slack}\n" in report


def test_progress_bar_on_a_terminal(capsys: pytest.CaptureFixture[str]) -> None:
    bar = Progress(4, enabled=True, delay=0.0)
    bar.update(2)
    bar.update(2)
    bar.close()
    err = capsys.readouterr().err
    assert "4/4 cases" in err and "#" * 30 in err
    quiet = Progress(4, enabled=False)
    quiet.update(4)
    quiet.close()
    assert capsys.readouterr().err == ""
    # not a terminal (pytest captures stderr): no bar by default
    default = Progress(4)
    default.update(4)
    default.close()
    assert capsys.readouterr().err == ""
    # a study finished before the delay shows nothing, even on a terminal
    quick = Progress(4, enabled=True, delay=30.0)
    quick.update(4)
    quick.close()
    assert capsys.readouterr().err == ""
    # ... and one running past it does (tqdm: n/total, elapsed, remaining)
    slow = Progress(4, enabled=True, delay=0.05)
    slow.update(1)
    time.sleep(0.1)
    slow.update(1)
    slow.close()
    err = capsys.readouterr().err
    assert "2/4 cases" in err and "eta" in err


def test_auto_scheduler_keeps_a_quick_study_in_process(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    def no_cluster(*args: object, **kwargs: object) -> None:
        raise AssertionError("a 27-case catenary study must not start worker processes")

    monkeypatch.setattr(scheduler, "_run_dask", no_cluster)
    src, grid, cases = _expand()
    summary = run_study(src, grid, tmp_path, scheduler="auto", progress=False)
    assert summary.n_computed == 27 and summary.n_failed == 0


def test_auto_scheduler_hands_a_long_study_to_workers(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    handed: list[tuple[int, str, float | None]] = []

    def fake_cluster(work, cases, scheduler, workers, on_done, *, per_case=None):  # noqa: ANN001, ANN202
        handed.append((len(cases), scheduler, per_case))
        on_done(run_chunk(cases))

    monkeypatch.setattr(scheduler, "_run_dask", fake_cluster)
    monkeypatch.setattr(scheduler, "AUTO_PROBE_SECONDS", 0.0)  # decide after one case
    monkeypatch.setattr(scheduler, "AUTO_PARALLEL_AFTER", 0.0)  # ... that anything is long
    monkeypatch.setattr(scheduler, "THREAD_PROBE_SECONDS", 0.0)  # one case a thread
    monkeypatch.setattr(scheduler, "THREADS_SCALE", 1e9)  # ... that never scale
    src, grid, cases = _expand()
    summary = run_study(src, grid, tmp_path, scheduler="auto", workers=2, progress=False)
    # one case probed alone, one on each of two threads, the rest to worker processes
    assert [h[:2] for h in handed] == [(24, "processes")] and handed[0][2] > 0
    assert summary.n_computed == 27 and summary.scheduler == "processes"
    first, counted = summary.report().splitlines()[:2]
    assert first.endswith("s (processes)")
    # method analytic has no batch kernel: every case counted, records or grid alike
    assert counted.startswith("27 cases solved by the general solver")


def test_scheduler_choice_follows_the_probe() -> None:
    from cablestudy.run.scheduler import Probe, choose_scheduler

    _, _, cases = _expand()  # 27 cases
    quick = Probe(cases, per_case=0.01)  # 0.27 s left: not worth starting anything
    assert choose_scheduler(quick, workers=2) == "synchronous"
    slow = Probe(cases, per_case=1.0, thread_speedup=1.9)  # 27 s, numba without the GIL
    assert choose_scheduler(slow, workers=2) == "threads"
    bound = Probe(cases, per_case=1.0, thread_speedup=1.05)  # the GIL serialises threads
    assert choose_scheduler(bound, workers=2) == "processes"
    assert choose_scheduler(bound, workers=1) == "synchronous"


def test_chunks_take_the_target_time_at_the_measured_cost() -> None:
    _, _, cases = _expand()
    many = [Case((i,), {}, cases[0].study, f"h{i}", f"s{i % 7}") for i in range(5000)]
    # 0.01 s a case: TARGET_TASK_SECONDS / 0.01 cases a task
    per_task = round(TARGET_TASK_SECONDS / 0.01)
    assert {len(c) for c in make_chunks(many, workers=2, per_case=0.01)} == {per_task}
    # 5 s a case: one case a task; 1 us a case: as many as load balance allows
    assert {len(c) for c in make_chunks(many, workers=2, per_case=5.0)} == {1}
    assert [len(c) for c in make_chunks(many, workers=2, per_case=1e-6)] == [625] * 8
    huge = [Case((i,), {}, cases[0].study, f"h{i}", "s") for i in range(100_000)]
    sizes = {len(c) for c in make_chunks(huge, workers=2, per_case=1e-7)}
    assert max(sizes) <= MAX_CHUNK_CASES


def test_probe_runs_each_case_once_in_doubling_chunks() -> None:
    _, _, cases = _expand()
    done: list[int] = []
    probe = probe_cost(cases, lambda chunk: done.append(chunk.n), seconds=1e9)
    assert done == [1, 2, 4, 8, 12] and probe.rest == []
    assert probe.per_case > 0


def test_time_limited_cases_fail_with_a_message_and_are_retried(tmp_path: Path) -> None:
    """A case over analysis.time_limit is a failure with a message (data NaN), and it is
    not cached: on a less loaded machine a re-run may finish it."""
    text = TEXT.replace("analysis:\n", "analysis:\n  time_limit: 1.0e-9\n")
    src, grid, cases = _expand(text)
    summary = run_study(src, grid, tmp_path, scheduler="synchronous", progress=False)
    ds = xr.load_dataset(summary.path)
    assert np.all(ds["status"] == 3)
    assert all(str(m).startswith("time limit") for m in ds["message"].values.ravel())
    assert np.all(np.isnan(ds["tension_a"]))
    assert "    27 x time limit" in summary.report()
    again = run_study(src, grid, tmp_path, scheduler="synchronous", progress=False)
    assert again.n_reused == 0 and again.n_computed == 27


def test_case_evaluation_refuses_features_its_solver_lacks() -> None:
    """Defence in depth: evaluate_case called without the CLI's check_supported must not
    quietly solve a current-loaded line with the still-water exact solver."""
    import yaml

    from cablestudy.analyses.evaluate import evaluate_case
    from cablestudy.study.grid import expand_grid
    from cablestudy.study.loader import parse_study_text

    data = {
        "name": "unsupported",
        "environment": {
            "fluid": "water",
            "current": [{"z": 0.0, "speed": 1.0, "heading_deg": 0.0}],
        },
        "line": {
            "segments": [
                {"length": 100.0, "diameter": 0.05, "mass_per_length": 5.0, "axial_stiffness": 1e8}
            ]
        },
        "ends": {
            "a": {"kind": "fixed", "position": [0.0, 0.0, 0.0]},
            "b": {"kind": "fixed", "position": [80.0, 0.0, -20.0]},
        },
        "analysis": {"static": {"method": "analytic"}},
    }
    cases = expand_grid(parse_study_text(yaml.safe_dump(data), "<x>")).cases()
    record = evaluate_case(cases[0])
    assert record.status != 0
    assert "analytic" in record.message and "current" in record.message


def test_the_cli_runs_every_study_through_the_one_runner(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A static sweep (a grid in chunks of rows, as arrays) and a modal sweep (its cases
    as records on the probing scheduler) both go through run.runner.run_study, and a
    re-run of each is all reused from its cache."""
    from cablestudy.cli import main
    from cablestudy.run import runner

    seen: list[tuple[bool, int]] = []
    real = runner.run_study

    def spy(src, grid, out, **kw):  # noqa: ANN001, ANN003, ANN202
        summary = real(src, grid, out, **kw)
        seen.append((grid.chunked, summary.n_reused))
        return summary

    monkeypatch.setattr(runner, "run_study", spy)
    modal = TEXT.replace("name: rn", "name: rm").replace(
        "nodes: 5}", "nodes: 5}\n  modal: {modes: 2, elements: 10}"
    )
    for label, text in (("static", TEXT), ("modal", modal)):
        cfg = tmp_path / f"{label}.yaml"
        cfg.write_text(text)
        for _ in range(2):
            args = ["run", str(cfg), "--out", str(tmp_path), "--no-progress"]
            assert main([*args, "--scheduler", "synchronous"]) == 0
    n = expand_grid(parse_study_text(TEXT, "rn.yaml")).size
    assert seen == [(True, 0), (True, n), (False, 0), (False, n)]


def test_a_value_inserted_into_the_sweep_reuses_the_cases_where_they_now_are(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A cached case is found by its content hash, not its place: after a value is
    inserted in the middle of an axis, the cached cases land at their new indices, and
    the dataset equals an uncached run of the edited study (wall times aside)."""
    src, grid, _ = _expand()
    run_study(src, grid, tmp_path / "c", scheduler="synchronous", progress=False)
    edited = TEXT.replace("[1.0e6, 1.0e7, 6.283e7]", "[1.0e6, 3.0e6, 1.0e7, 6.283e7]")
    src2, grid2, _ = _expand(edited)
    counter = _count_evaluations(monkeypatch)
    again = run_study(src2, grid2, tmp_path / "c", scheduler="synchronous", progress=False)
    assert counter["cases"] == 9 and again.n_reused == 27
    plain = run_study(
        src2, grid2, tmp_path / "plain", scheduler="synchronous", use_cache=False, progress=False
    )
    got, ref = xr.load_dataset(again.path), xr.load_dataset(plain.path)
    xr.testing.assert_identical(
        got.drop_vars("wall_time"),
        ref.drop_vars("wall_time").assign_attrs(history=got.attrs["history"]),
    )
