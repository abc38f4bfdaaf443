"""The runner never hangs and never shows a traceback for a user's mistake or the
machine's state (issue 21, item 5), through the real command line: each case prints one
line naming the path or address and what went wrong, with exit status 2 (the user's to
fix) or 1 (the machine's state). Network tests use 127.0.0.1 only, with a connect
timeout of 0.5 s; each is bounded by :data:`HANG` seconds."""

from __future__ import annotations

import errno
import http.server
import os
import re
import signal
import socket
import subprocess
import threading
import time
from collections.abc import Iterator
from pathlib import Path

import pytest
import xarray as xr

from cablestudy.cli import main
from cablestudy.run import outputs, runner

#: a 550 m wire from an anchor 190 m down to a fairlead 10 m down, two distances: quick
#: cases of a static grid (cablestudy.analyses.static_grid: method catenary on the compiled array
#: route,
#: analytic solved per case in the chunk)
STUDY = """\
name: wire
environment: {fluid: water, depth: 200.0}
line:
  segments:
    - {length: 550.0, diameter: 0.076, mass_per_length: 24.0, axial_stiffness: 3.3e8}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -190.0]}
  b: {kind: fixed, position: [500.0, 0.0, -10.0]}
analysis:
  static: {method: METHOD, nodes: 21}
sweep:
  ends.b.position.0: {values: VALUES, name: distance}
"""
#: seconds after which a test that should take well under one counts as hung
HANG = 30
TIMEOUT = "0.5"


@pytest.fixture(scope="module", autouse=True)
def _client_imported() -> None:
    """Import dask.distributed (the client a --scheduler address gets) once, before any
    test's clock and alarm start: under pytest-xdist any test of this file can be the
    first of its worker to import it, which takes seconds on a loaded machine and is not
    the handshake the timed tests bound."""
    import dask.distributed  # noqa: F401

    from cablestudy.run import remote  # noqa: F401


@pytest.fixture(autouse=True)
def _no_hang() -> Iterator[None]:
    """Fail (not hang) a test that blocks for :data:`HANG` seconds."""

    def hung(signum: int, frame: object) -> None:
        raise TimeoutError(f"hung for {HANG} s")

    old = signal.signal(signal.SIGALRM, hung)
    signal.alarm(HANG)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)


def _study(tmp_path: Path, method: str = "analytic", values: str = "[500.0, 520.0]") -> Path:
    tmp_path.mkdir(parents=True, exist_ok=True)
    cfg = tmp_path / "wire.yaml"
    cfg.write_text(STUDY.replace("METHOD", method).replace("VALUES", values))
    return cfg


def _case_path_study(tmp_path: Path) -> Path:
    """The same two distances swept as whole end positions (values that are not numbers):
    a sweep the grid does not take, run case by case with the case cache."""
    cfg = _study(tmp_path)
    cfg.write_text(
        cfg.read_text().replace(
            "ends.b.position.0: {values: [500.0, 520.0], name: distance}",
            "ends.b.position: {values: [[500.0, 0.0, -10.0], [520.0, 0.0, -10.0]], name: distance}",
        )
    )
    return cfg


def _run(capsys: pytest.CaptureFixture[str], *args: str) -> tuple[int, str, str]:
    code = main(["run", *args])
    captured = capsys.readouterr()
    return code, captured.out, captured.err


@pytest.fixture
def no_work(monkeypatch: pytest.MonkeyPatch) -> None:
    """Any case solved fails the test: the check must come before any work."""

    def refuse(*args: object, **kwargs: object) -> None:
        raise AssertionError("work started before the check")

    monkeypatch.setattr(runner, "run_study", refuse)  # the one runner of every study


# --- the scheduler address --------------------------------------------------------------


@pytest.mark.parametrize(
    ("address", "what"),
    [
        (
            "tls://127.0.0.1:8786",
            "tls:// needs the cluster's certificates, which cablestudy does not take; give "
            "the scheduler's tcp:// address",
        ),
        ("udp://127.0.0.1:8786", "unknown scheme 'udp://'; allowed: tcp://host:port"),
        ("tcp://127.0.0.1", "no port (tcp://host:port)"),
        ("tcp://:8786", "no host (tcp://host:port)"),
        ("tcp://127.0.0.1:70000", "not an address tcp://host:port with a port from 1 to 65535"),
        ("tcp://127.0.0.1:http", "not an address tcp://host:port with a port from 1 to 65535"),
    ],
)
def test_a_malformed_scheduler_address_is_one_line_exit_2(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], no_work: None, address: str, what: str
) -> None:
    code, _, err = _run(
        capsys, str(_study(tmp_path)), "--out", str(tmp_path), "--scheduler", address
    )
    assert (code, err) == (2, f"--scheduler {address}: {what}\n")


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


@pytest.fixture
def silent_listener() -> Iterator[str]:
    """A port that accepts connections (the kernel completes them) and never says a
    word."""
    srv = socket.socket()
    srv.bind(("127.0.0.1", 0))
    srv.listen(8)
    try:
        yield f"tcp://127.0.0.1:{srv.getsockname()[1]}"
    finally:
        srv.close()


@pytest.fixture
def web_server() -> Iterator[str]:
    """A local HTTP server (what a dashboard port answers): dask's client reading its
    reply as a message length asked for 3.07 EiB."""
    httpd = http.server.HTTPServer(("127.0.0.1", 0), http.server.BaseHTTPRequestHandler)
    thread = threading.Thread(target=httpd.serve_forever, daemon=True)
    thread.start()
    try:
        yield f"tcp://127.0.0.1:{httpd.server_address[1]}"
    finally:
        httpd.shutdown()
        httpd.server_close()


NO_HANDSHAKE = (
    "accepted the connection but sent no dask handshake within 0.5 s (not a dask "
    "scheduler, or one too busy to answer)"
)


@pytest.mark.parametrize("server", ["silent_listener", "web_server"])
def test_an_address_that_never_answers_as_a_scheduler_fails_in_the_timeout(
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
    request: pytest.FixtureRequest,
    no_work: None,
    server: str,
) -> None:
    address = request.getfixturevalue(server)
    cfg = str(_study(tmp_path))
    t0 = time.monotonic()
    code, _, err = _run(
        capsys, cfg, "--out", str(tmp_path), "--scheduler", address, "--connect-timeout", TIMEOUT
    )
    elapsed = time.monotonic() - t0
    assert (code, err) == (1, f"--scheduler {address}: {NO_HANDSHAKE}\n")
    # the whole handshake is bounded by the timeout: 0.5 s, plus loading the study
    assert elapsed < 10.0, f"took {elapsed:.1f} s"


def test_the_connect_timeout_comes_from_the_environment(
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
    monkeypatch: pytest.MonkeyPatch,
    silent_listener: str,
    no_work: None,
) -> None:
    monkeypatch.setenv("CABLESTUDY_CONNECT_TIMEOUT", "0.25")
    cfg = str(_study(tmp_path))
    code, _, err = _run(capsys, cfg, "--out", str(tmp_path), "--scheduler", silent_listener)
    assert code == 1
    assert err == f"--scheduler {silent_listener}: {NO_HANDSHAKE.replace('0.5 s', '0.25 s')}\n"
    monkeypatch.setenv("CABLESTUDY_CONNECT_TIMEOUT", "soon")
    code, _, err = _run(capsys, cfg, "--out", str(tmp_path), "--scheduler", silent_listener)
    assert (code, err) == (2, "$CABLESTUDY_CONNECT_TIMEOUT 'soon': not a number of seconds\n")


def test_nothing_listening_is_one_line_exit_1(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], no_work: None
) -> None:
    address = f"tcp://127.0.0.1:{_free_port()}"
    cfg = str(_study(tmp_path))
    code, _, err = _run(
        capsys, cfg, "--out", str(tmp_path), "--scheduler", address, "--connect-timeout", TIMEOUT
    )
    assert (code, err) == (1, f"--scheduler {address}: cannot connect (Connection refused)\n")


def test_a_live_scheduler_without_workers_fails_in_the_timeout(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], no_work: None
) -> None:
    from dask.distributed import LocalCluster

    with LocalCluster(
        n_workers=0,
        processes=False,
        protocol="tcp://",
        host="127.0.0.1",
        dashboard_address=None,
        silence_logs=50,
    ) as cluster:
        address = cluster.scheduler_address
        t0 = time.monotonic()
        code, _, err = _run(
            capsys,
            str(_study(tmp_path)),
            "--out",
            str(tmp_path),
            "--scheduler",
            address,
            "--connect-timeout",
            TIMEOUT,
        )
        elapsed = time.monotonic() - t0
    assert (code, err) == (
        1,
        f"--scheduler {address}: the scheduler answers but has no workers (none joined "
        "within 0.5 s)\n",
    )
    assert elapsed < 10.0, f"took {elapsed:.1f} s"
    assert not (tmp_path / "wire.nc").exists()


# --- output paths -------------------------------------------------------------------------


def test_output_paths_are_checked_before_any_work(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], no_work: None
) -> None:
    cfg = str(_study(tmp_path))
    a_file = tmp_path / "a-file"
    a_file.write_text("not a folder")
    code, _, err = _run(capsys, cfg, "--out", str(a_file))
    assert (code, err) == (2, f"--out {a_file}: is a file, not a folder\n")

    taken = tmp_path / "taken"
    (taken / "wire.nc").mkdir(parents=True)
    code, _, err = _run(capsys, cfg, "--out", str(taken))
    assert (code, err) == (
        2,
        f"--out {taken}: {taken / 'wire.nc'} is a folder, not a result file\n",
    )

    under_a_file = a_file / "results"
    code, _, err = _run(capsys, cfg, "--out", str(under_a_file))
    assert (code, err) == (2, f"--out {under_a_file}: cannot create the folder (Not a directory)\n")

    # /proc takes no new folder, even from root (a chmod'ed folder would not stop root)
    code, _, err = _run(capsys, cfg, "--out", "/proc/cablestudy-results")
    assert (code, err) == (
        2,
        "--out /proc/cablestudy-results: cannot create the folder (No such file or directory)\n",
    )


def test_an_unwritable_folder_is_refused_before_any_work(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], no_work: None
) -> None:
    """/proc/self exists and takes no new file (for root too)."""
    code, _, err = _run(capsys, str(_study(tmp_path)), "--out", "/proc/self")
    assert code == 2
    assert re.fullmatch(r"--out /proc/self: cannot write in the folder \([^)]+\)\n", err), err


# --- a full disk ----------------------------------------------------------------------------


def _leftovers(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.rglob("*.tmp"))


@pytest.mark.parametrize("method", ["analytic", "catenary"])
def test_a_full_disk_at_the_result_is_named_as_such(
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
    monkeypatch: pytest.MonkeyPatch,
    method: str,
) -> None:
    """The netCDF writer raising ENOSPC (as the OS reports a full disk), on both paths."""
    import netCDF4

    def full(*args: object, **kwargs: object) -> None:
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(netCDF4, "Dataset", full)
    out = tmp_path / "out"
    cfg = str(_study(tmp_path, method))
    code, _, err = _run(capsys, cfg, "--out", str(out), "--scheduler", "synchronous")
    assert (code, err) == (
        1,
        f"cannot write the results: no space left on device at {out / 'wire.nc'}\n",
    )
    assert not (out / "wire.nc").exists() and _leftovers(out) == []


def test_an_hdf_error_on_a_full_disk_is_named_as_such(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    """HDF5 reports a full disk as "NetCDF: HDF error", without the errno: the free space
    of the file system (here reported as none) tells."""
    import shutil

    import netCDF4

    def hdf_error(*args: object, **kwargs: object) -> None:
        raise RuntimeError("NetCDF: HDF error")

    real = shutil.disk_usage
    monkeypatch.setattr(netCDF4, "Dataset", hdf_error)
    monkeypatch.setattr(outputs.shutil, "disk_usage", lambda p: real(p)._replace(free=4096))
    out = tmp_path / "out"
    code, _, err = _run(capsys, str(_study(tmp_path)), "--out", str(out), "--no-cache")
    assert (code, err) == (
        1,
        f"cannot write the results: no space left on device at {out / 'wire.nc'}\n",
    )


def test_a_full_disk_at_the_cache_is_named_as_such(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    def full(fd: int) -> None:
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(os, "fsync", full)
    out = tmp_path / "out"
    cfg = str(_case_path_study(tmp_path))
    code, _, err = _run(capsys, cfg, "--out", str(out), "--scheduler", "synchronous")
    assert code == 1
    cache = out / ".cache" / "wire"
    assert re.fullmatch(
        rf"cannot write the results: no space left on device at {re.escape(str(cache))}"
        r"/grid-[0-9a-f]{32}-[0-9a-f]{64}\.npz\n",
        err,
    ), err
    assert _leftovers(out) == []


# --- the cache ------------------------------------------------------------------------------


def _odd(path: Path) -> str:
    return (
        f"warning: cache entry {path} is not a regular file (a folder, link, FIFO or "
        "device); skipped and left in place\n"
    )


def test_odd_entries_named_like_case_cache_chunks_are_skipped(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """A folder and a FIFO named like chunk files: each run warns and finishes (a FIFO
    opened for reading would block until a writer came), and leaves them in place."""
    cfg = str(_case_path_study(tmp_path))
    cache = tmp_path / ".cache" / "wire"
    cache.mkdir(parents=True)
    folder = cache / f"grid-{'a' * 32}-{'a' * 64}.npz"
    folder.mkdir()
    fifo = cache / f"grid-{'b' * 32}-{'b' * 64}.npz"
    os.mkfifo(fifo)
    for _ in range(2):
        code, out, err = _run(capsys, cfg, "--out", str(tmp_path), "--scheduler", "synchronous")
        assert code == 0 and "wrote" in out
        assert err == _odd(folder) + _odd(fifo)
        assert folder.is_dir() and fifo.is_fifo()
    assert "(0 computed, 2 reused from cache)" in out


def test_odd_entries_named_like_grid_chunks_are_skipped(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    cfg = str(_study(tmp_path, "catenary"))
    code, _, _ = _run(capsys, cfg, "--out", str(tmp_path))
    assert code == 0
    cache = tmp_path / ".cache" / "wire"
    (chunk,) = cache.glob("grid-*.npz")
    odd = cache / f"{chunk.name[:38]}{'c' * 64}.npz"  # the same chunk key, another hash
    chunk.unlink()
    odd.mkdir()
    code, out, err = _run(capsys, cfg, "--out", str(tmp_path))
    assert code == 0 and "(2 computed, 0 reused from cache)" in out
    assert err == _odd(odd)
    assert odd.is_dir()


def _dead_pid() -> int:
    proc = subprocess.Popen(["true"])
    proc.wait()
    return proc.pid


def test_temporary_files_of_killed_runs_are_removed_and_live_ones_kept(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    cfg = str(_study(tmp_path))
    host = outputs._host()
    dead, alive = _dead_pid(), os.getpid()
    cache = tmp_path / ".cache" / "wire"
    cache.mkdir(parents=True)
    legacy = tmp_path / ".wire.nc.k3j2h1.tmp"  # an earlier version's: no owner in its name
    legacy.write_bytes(b"half a file")
    hour_ago = time.time() - 3600
    os.utime(legacy, (hour_ago, hour_ago))
    stale = [
        legacy,
        tmp_path / f".wire.nc.pid{dead}@{host}.x1.tmp",
        tmp_path / f".wire.database.nc.pid{dead}@{host}.x2.tmp",
        cache / f".chunk-pid{dead}@{host}.x3.tmp",
        cache / f".grid-pid{dead}@{host}.x4.tmp",
    ]
    scratch = tmp_path / f".wire-chunks-pid{dead}@{host}.x5"
    live = [
        tmp_path / f".wire.nc.pid{alive}@{host}.y1.tmp",  # a run still writing
        tmp_path / f".wire.nc.pid{dead}@elsewhere.y2.tmp",  # another machine's
        tmp_path / ".other.nc.z1.tmp",  # another study's
    ]
    for path in stale + live:
        if not path.exists():
            path.write_bytes(b"partial")
    scratch.mkdir()
    (scratch / "grid-part.npz").write_bytes(b"partial")
    code, out, err = _run(capsys, cfg, "--out", str(tmp_path))
    assert code == 0 and "wrote" in out
    assert sorted(err.splitlines()) == sorted(
        f"warning: removed {p}, left by a run that was stopped while writing it"
        for p in [*stale, scratch]
    )
    assert not any(p.exists() for p in [*stale, scratch])
    assert all(p.exists() for p in live)


# --- concurrent runs ------------------------------------------------------------------------


@pytest.mark.parametrize("method", ["analytic", "catenary"])
def test_a_run_never_removes_cache_files_while_another_run_holds_the_cache(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], method: str
) -> None:
    """Two versions of a study run into one folder. While another run holds the cache
    (its shared lock, as every run takes), a run removes no file it did not make; alone,
    it prunes the other version's files, as before."""
    first = str(_study(tmp_path / "v1", method, "[500.0, 520.0]"))
    second = str(_study(tmp_path / "v2", method, "[540.0, 560.0]"))
    out = tmp_path / "out"
    cache = out / ".cache" / "wire"
    assert _run(capsys, first, "--out", str(out))[0] == 0
    before = set(cache.glob("*.npz"))
    assert before
    with outputs.CacheLock(cache):  # another run of the study, still going
        assert _run(capsys, second, "--out", str(out))[0] == 0
        after = set(cache.glob("*.npz"))
        assert before < after  # the first version's files all kept, the second's added
    code, printed, _ = _run(capsys, second, "--out", str(out))
    assert code == 0 and "(0 computed, 2 reused from cache)" in printed
    pruned = set(cache.glob("*.npz"))
    assert pruned and not (pruned & before)  # alone: the first version's files pruned
    ds = xr.load_dataset(out / "wire.nc")
    assert ds["distance"].values.tolist() == [540.0, 560.0]


def test_the_temporary_file_of_a_writer_killed_mid_write_is_removed(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """A process writing wire.nc the way a run does is killed (SIGKILL) in the middle:
    its temporary file stays behind, and the next run removes it."""
    import sys

    root = Path(__file__).resolve().parents[2]
    code = (
        "import sys, time; from cablestudy.run.writer import _atomically; "
        "_atomically(sys.argv[1], lambda tmp: time.sleep(60))"
    )
    env = {**os.environ, "PYTHONPATH": str(root)}
    proc = subprocess.Popen([sys.executable, "-c", code, str(tmp_path / "wire.nc")], env=env)
    try:
        deadline = time.monotonic() + 20.0
        while not list(tmp_path.glob(".wire.nc.*.tmp")) and time.monotonic() < deadline:
            time.sleep(0.05)
        (left,) = tmp_path.glob(".wire.nc.*.tmp")
    finally:
        proc.kill()
        proc.wait()
    assert left.exists()
    code, out, err = _run(capsys, str(_study(tmp_path)), "--out", str(tmp_path))
    assert code == 0 and "wrote" in out
    assert err == f"warning: removed {left}, left by a run that was stopped while writing it\n"
    assert not left.exists() and (tmp_path / "wire.nc").is_file()
