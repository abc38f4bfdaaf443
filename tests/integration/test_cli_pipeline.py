"""YAML -> netCDF through the command line, on the synchronous scheduler, on a local
dask.distributed cluster (--scheduler processes --workers 2) and on a running cluster
given by its address (--scheduler tcp://...)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cablestudy.cli import main

ROOT = Path(__file__).resolve().parents[2]

#: a small sweep (3 spans x 2 stiffnesses, one case stretched taut) for the schedulers
SWEEP = """\
name: pipe
description: integration sweep
environment: {fluid: air}
line:
  segments:
    - {length: 100.0, diameter: 0.02, mass_per_length: 2.466, axial_stiffness: 6.283e7}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [92.5, 0.0, -8.6]}
analysis:
  static: {method: analytic, nodes: 21}
sweep:
  ends.b.position.0: {values: [60.0, 92.5, 100.5], name: span}
  line.segments.0.axial_stiffness: [1.0e6, 6.283e7]
"""


def _run(tmp_path: Path, capsys: pytest.CaptureFixture[str], *extra: str) -> xr.Dataset:
    tmp_path.mkdir(parents=True, exist_ok=True)
    cfg = tmp_path / "pipe.yaml"
    cfg.write_text(SWEEP)
    out = tmp_path / "out"
    assert main(["run", str(cfg), "--out", str(out), "--no-cache", *extra]) == 0
    assert "wrote" in capsys.readouterr().out
    return xr.load_dataset(out / "pipe.nc")


def _check_physics(ds: xr.Dataset) -> None:
    assert dict(ds.sizes) == {"span": 3, "axial_stiffness": 2, "s": 21, "component": 3}
    assert np.all(ds["status"] == 0)
    w = (2.466 - 1.225 * math.pi * 0.02**2 / 4) * 9.80665
    # the supports carry the whole weight; end tension is the end force's magnitude
    total = ds["force_a"] + ds["force_b"]
    np.testing.assert_allclose(total.sel(component="z"), -w * 100.0, rtol=1e-12)
    np.testing.assert_allclose(
        np.hypot(*(ds["force_a"].sel(component=c) for c in "xz")),
        ds["tension"].isel(s=0),
        rtol=1e-12,
    )
    # the line ends where end B was put
    np.testing.assert_allclose(
        ds["x"].isel(s=-1), ds["span"].broadcast_like(ds["x"].isel(s=-1)), atol=1e-9
    )


def test_catenary_in_air_study_through_the_cli(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "results"
    assert (
        main(
            [
                "run",
                str(ROOT / "configs" / "catenary-in-air.yaml"),
                "--out",
                str(out),
                "--scheduler",
                "synchronous",
            ]
        )
        == 0
    )
    ds = xr.load_dataset(out / "catenary-in-air.nc")
    assert ds["x"].dims == ("s",) and ds.sizes["s"] == 101
    assert ds["x"].attrs["units"] == "m" and ds["tension"].attrs["units"] == "N"
    assert int(ds["status"]) == 0 and str(ds["message"].item()) == ""
    np.testing.assert_allclose([ds["x"][-1], ds["z"][-1]], [92.5, -8.6], atol=1e-9)
    assert ds.attrs["study_name"] == "catenary-in-air"
    assert ds.attrs["study_yaml"] == (ROOT / "configs" / "catenary-in-air.yaml").read_text()
    assert "wrote" in capsys.readouterr().out


def test_swept_study_synchronous(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    ds = _run(tmp_path, capsys, "--scheduler", "synchronous")
    _check_physics(ds)
    assert ds["span"].attrs["units"] == "m" and ds["axial_stiffness"].attrs["units"] == "N"
    # stretched taut (chord 100.87 m > 100 m): tension ~ EA * strain
    taut = ds.sel(span=100.5, axial_stiffness=6.283e7)
    strain = math.hypot(100.5, 8.6) / 100.0 - 1.0
    assert float(taut["tension_a"]) == pytest.approx(6.283e7 * strain, rel=0.01)


def test_swept_study_on_a_local_distributed_cluster(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    ds = _run(tmp_path, capsys, "--scheduler", "processes", "--workers", "2")
    _check_physics(ds)
    ref = _run(tmp_path / "sync", capsys, "--scheduler", "synchronous")
    skip = ["wall_time"]
    xr.testing.assert_equal(ds.drop_vars(skip), ref.drop_vars(skip))


def test_swept_study_on_a_running_scheduler_address(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from dask.distributed import LocalCluster

    with LocalCluster(
        n_workers=1,
        threads_per_worker=2,
        processes=True,
        protocol="tcp://",
        dashboard_address=None,
        silence_logs=50,
    ) as cluster:
        address = cluster.scheduler_address
        assert address.startswith("tcp://")
        ds = _run(tmp_path, capsys, "--scheduler", address)
    _check_physics(ds)


def test_unknown_scheduler_is_refused(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    cfg = tmp_path / "pipe.yaml"
    cfg.write_text(SWEEP)
    assert main(["run", str(cfg), "--scheduler", "spark"]) == 2
    assert "allowed are auto, synchronous, threads, processes" in capsys.readouterr().err


def test_shipped_span_stiffness_sweep(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """configs/catenary-sweep.yaml end to end: a (span x axial_stiffness) dataset in which
    the end tension grows with the span (the line is pulled straighter) and, once the chord
    exceeds the unstretched length, with the axial stiffness (T ~ EA * strain)."""
    cfg = ROOT / "configs" / "catenary-sweep.yaml"
    assert main(["validate", str(cfg)]) == 0
    assert "328 cases (span=82, axial_stiffness=4)" in capsys.readouterr().out
    assert main(["run", str(cfg), "--out", str(tmp_path), "--scheduler", "synchronous"]) == 0
    ds = xr.load_dataset(tmp_path / "catenary-sweep.nc")
    assert dict(ds.sizes) == {"span": 82, "axial_stiffness": 4, "s": 101, "component": 3}
    assert np.all(ds["status"] == 0)
    assert np.all(ds["tension_a"].diff("span") > 0)
    taut = ds["tension_a"].sel(span=100.5)  # chord 100.87 m > 100 m
    assert np.all(taut.diff("axial_stiffness") > 0)
    strain = math.hypot(100.5, 8.6) / 100.0 - 1.0
    # the stiff steel wire barely stretches beyond the chord: T ~ EA strain within 1 %
    assert float(taut.sel(axial_stiffness=6.283e7)) == pytest.approx(6.283e7 * strain, rel=0.01)


def test_unreachable_scheduler_is_a_clear_error(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    cfg = tmp_path / "pipe.yaml"
    cfg.write_text(SWEEP)
    address = "tcp://127.0.0.1:9"  # the discard port: nothing listens on loopback
    args = ["run", str(cfg), "--out", str(tmp_path), "--scheduler", address]
    code = main([*args, "--connect-timeout", "1"])
    assert code == 1
    assert (
        capsys.readouterr().err == f"--scheduler {address}: cannot connect (Connection refused)\n"
    )
    assert not (tmp_path / "pipe.nc").exists()
