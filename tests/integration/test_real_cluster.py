"""A real dask.distributed cluster started from its command-line tools (``dask scheduler``,
two ``dask worker`` processes, on 127.0.0.1 only): a study sent to it with ``--scheduler
tcp://...`` finishes with every case computed, the same as a serial run, even when one
worker is killed in the middle of the study; an unreachable address fails in seconds."""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cablestudy.run.remote import DEFAULT_TIMEOUT

ROOT = Path(__file__).resolve().parents[2]
BIN = Path(sys.executable).parent
#: every wait in this file is bounded by this [s]
LIMIT = 120.0

#: twelve time-domain cases of the Moustafa cable, each a fraction of a second
STUDY = """\
name: cluster
environment: {fluid: water}
line:
  segments:
    - {length: 10.9774, diameter: 0.01, mass_per_length: 0.61, axial_stiffness: 7.854e+6}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [10.792, 0.0, 0.0]}
analysis:
  static: {method: analytic, nodes: 21}
  dynamic:
    excitation: {end: b, direction: [1.0, 0.0, 0.0], amplitude: 0.05, frequency: 0.5}
    method: time
sweep:
  analysis.dynamic.excitation.amplitude: [0.05, 0.1]
  analysis.dynamic.excitation.frequency: {start: 0.3, stop: 0.8, num: 6}
"""


def _env() -> dict[str, str]:
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT), env.get("PYTHONPATH", "")]).rstrip(os.pathsep)
    return env


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def _stop(proc: subprocess.Popen[bytes]) -> None:
    """End a process this test started, with everything it started (its own session)."""
    if proc.poll() is None:
        os.killpg(proc.pid, signal.SIGTERM)
        try:
            proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait(timeout=10)


def _wait_for_workers(address: str, n: int) -> None:
    from dask.distributed import Client

    with Client(address, timeout=LIMIT) as client:
        client.wait_for_workers(n, timeout=LIMIT)


@pytest.fixture
def cluster(tmp_path: Path) -> Iterator[tuple[str, list[subprocess.Popen[bytes]]]]:
    """``dask scheduler`` and two single-threaded ``dask worker`` processes on 127.0.0.1;
    yields the scheduler address and the worker processes (each in its own session, so
    that it can be killed with its nanny)."""
    port = _free_port()
    address = f"tcp://127.0.0.1:{port}"
    log = open(tmp_path / "cluster.log", "wb")  # noqa: SIM115 - closed below
    common = {"env": _env(), "stdout": log, "stderr": log, "start_new_session": True}
    procs = [
        subprocess.Popen(
            [str(BIN / "dask"), "scheduler", "--host", "127.0.0.1", "--port", str(port)]
            + ["--no-dashboard", "--no-show"],
            **common,
        )
    ]
    try:
        for _ in range(2):
            procs.append(
                subprocess.Popen(
                    [str(BIN / "dask"), "worker", address, "--host", "127.0.0.1"]
                    + ["--nthreads", "1", "--no-dashboard", "--death-timeout", "60"],
                    **common,
                )
            )
        _wait_for_workers(address, 2)
        yield address, procs[1:]
    finally:
        for proc in reversed(procs):
            _stop(proc)
        log.close()


def _cli(*args: str) -> subprocess.Popen[bytes]:
    return subprocess.Popen(
        [str(BIN / "cablestudy"), *args],
        env=_env(),
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        start_new_session=True,
    )


def test_study_survives_a_worker_killed_mid_study(
    tmp_path: Path, cluster: tuple[str, list[subprocess.Popen[bytes]]]
) -> None:
    from dask.distributed import Client

    address, workers = cluster
    cfg = tmp_path / "cluster.yaml"
    cfg.write_text(STUDY)
    run = _cli(
        "run", str(cfg), "--out", str(tmp_path / "dist"), "--no-cache", "--scheduler", address
    )
    killed = False
    try:
        with Client(address, timeout=LIMIT) as client:
            # the worker processes by address, to kill the one that is busy
            pids = client.run(os.getpid)
            t0 = time.monotonic()
            while time.monotonic() - t0 < LIMIT and run.poll() is None:
                busy = {w: keys for w, keys in client.processing().items() if keys}
                if len(busy) == 2:  # the study is under way on both workers
                    victim_pid = pids[sorted(busy)[0]]
                    victim = next(p for p in workers if os.getpgid(victim_pid) == os.getpgid(p.pid))
                    os.killpg(victim.pid, signal.SIGKILL)  # the worker and its nanny
                    killed = True
                    break
                time.sleep(0.005)
        out, err = run.communicate(timeout=LIMIT)
    finally:
        _stop(run)
    assert killed, "the study ended before both workers were busy"
    assert run.returncode == 0, err.decode()
    assert "12 cases (12 computed" in out.decode() and "0 failed" in out.decode()

    serial = subprocess.run(
        [str(BIN / "cablestudy"), "run", str(cfg), "--out", str(tmp_path / "serial")]
        + ["--no-cache", "--scheduler", "synchronous"],
        env=_env(),
        capture_output=True,
        timeout=LIMIT,
        check=True,
    )
    assert b"0 failed" in serial.stdout
    dist = xr.load_dataset(tmp_path / "dist" / "cluster.nc")
    ref = xr.load_dataset(tmp_path / "serial" / "cluster.nc")
    assert np.all(dist["status"] == 0) and np.all(np.isfinite(dist["tension_max"]))
    skip = ["wall_time"]
    xr.testing.assert_identical(
        dist.drop_vars(skip), ref.drop_vars(skip).assign_attrs(history=dist.attrs["history"])
    )


def test_unreachable_scheduler_fails_in_seconds_naming_the_address(tmp_path: Path) -> None:
    cfg = tmp_path / "cluster.yaml"
    cfg.write_text(STUDY)
    address = f"tcp://127.0.0.1:{_free_port()}"  # nothing listens there
    t0 = time.monotonic()
    proc = subprocess.run(
        [str(BIN / "cablestudy"), "run", str(cfg), "--out", str(tmp_path), "--scheduler", address],
        env=_env(),
        capture_output=True,
        timeout=LIMIT,
    )
    elapsed = time.monotonic() - t0
    assert proc.returncode == 1
    assert proc.stderr.decode() == f"--scheduler {address}: cannot connect (Connection refused)\n"
    # a hang detector, not a timing: the connect timeout is DEFAULT_TIMEOUT (10 s), and
    # process start and imports add a few seconds that a loaded machine stretches
    assert elapsed < 3.0 * DEFAULT_TIMEOUT, f"took {elapsed:.1f} s"
    assert not (tmp_path / "cluster.nc").exists()


def test_local_workers_leave_ctrl_c_to_the_run() -> None:
    """Ctrl-C reaches every process of the terminal's group: the local cluster's worker
    processes start with SIGINT ignored, so only the run itself stops (it says so and
    closes the cluster) instead of every worker printing a traceback; this process's own
    handler is back in place afterwards."""
    from dask.distributed import Client

    from cablestudy.run.scheduler import PROCESSES, _local_cluster

    before = signal.getsignal(signal.SIGINT)
    cluster = _local_cluster(PROCESSES, 1)
    try:
        assert signal.getsignal(signal.SIGINT) is before
        with Client(cluster) as client:
            seen = client.run(lambda: int(signal.getsignal(signal.SIGINT)))
        assert list(seen.values()) == [int(signal.SIG_IGN)]
    finally:
        cluster.close()
