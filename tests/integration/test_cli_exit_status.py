"""`cablestudy run`'s exit status when cases fail (docs/guide/cli.md): a study in which no
case succeeded still writes its dataset, every failure recorded, and exits with
EXIT_NO_CASE_SUCCEEDED (3); a study where some cases succeeded exits 0."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cablestudy.cli import EXIT_NO_CASE_SUCCEEDED, main

#: a 550 m wire from an anchor 200 m down (10 m above the seabed) to a fairlead 10 m
#: down: at 250 and 300 m apart the path down to the seabed, along it and up is 450 m or
#: less, so the line lies slack on the seabed and its laid shape is undetermined (a
#: failure, status and message); at 500 m it hangs as a catenary
WIRE = """\
name: wire
environment: {fluid: water, depth: 200.0}
line:
  segments:
    - {length: 550.0, diameter: 0.076, mass_per_length: 24.0, axial_stiffness: 3.3e8}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -190.0]}
  b: {kind: fixed, position: [500.0, 0.0, -10.0]}
analysis:
  static: {nodes: 51}
sweep:
  ends.b.position.0: {values: VALUES, name: distance}
"""


def _study(tmp_path: Path, values: str) -> Path:
    cfg = tmp_path / "wire.yaml"
    cfg.write_text(WIRE.replace("VALUES", values))
    return cfg


def test_a_run_where_every_case_failed_exits_3_with_its_dataset(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    cfg = _study(tmp_path, "[250.0, 300.0]")
    code = main(["run", str(cfg), "--out", str(tmp_path), "--scheduler", "synchronous"])
    assert code == EXIT_NO_CASE_SUCCEEDED == 3
    err = capsys.readouterr().err
    assert "no case succeeded: all 2 failed" in err and "exit status 3" in err
    ds = xr.load_dataset(tmp_path / "wire.nc")  # written, failures recorded
    assert np.all(ds["status"].values != 0)
    assert all("lies slack on the seabed" in str(m) for m in ds["message"].values)
    assert ds.attrs["cases"] == ds.attrs["cases_failed"] == 2
    assert np.all(np.isnan(ds["tension"].values))  # a failed case is NaN, never dropped


def test_a_run_where_some_cases_failed_exits_0(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    cfg = _study(tmp_path, "[300.0, 500.0]")
    code = main(["run", str(cfg), "--out", str(tmp_path), "--scheduler", "synchronous"])
    assert code == 0
    assert "no case succeeded" not in capsys.readouterr().err
    ds = xr.load_dataset(tmp_path / "wire.nc")
    assert ds["status"].values.tolist()[1] == 0 and ds["status"].values.tolist()[0] != 0
    assert ds.attrs["cases_failed"] == 1


def test_the_process_exit_status_is_the_commands(tmp_path: Path) -> None:
    """The installed entry point hands the status to the shell (python -m cablestudy, the
    same main), here with the case-by-case runner (method shooting, not the arrays)."""
    cfg = tmp_path / "wire.yaml"
    cfg.write_text(
        WIRE.replace("VALUES", "[250.0, 300.0]").replace("nodes: 51", "nodes: 51, method: shooting")
    )
    env = {**os.environ, "PYTHONPATH": str(Path(__file__).resolve().parents[2])}
    run = subprocess.run(
        [sys.executable, "-m", "cablestudy", "run", str(cfg), "--out", str(tmp_path)],
        capture_output=True,
        text=True,
        env=env,
        timeout=300,
        check=False,
    )
    assert run.returncode == EXIT_NO_CASE_SUCCEEDED, run.stderr
    assert (tmp_path / "wire.nc").is_file()


def test_the_failures_are_listed_under_their_heading(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """The run's summary lists the failures under "failures by message:" also when a line
    on the general solver's cases comes first (these cases touch the seabed: no batch
    kernel takes them)."""
    cfg = _study(tmp_path, "[250.0, 300.0]")
    main(["run", str(cfg), "--out", str(tmp_path), "--scheduler", "synchronous"])
    out = capsys.readouterr().out
    assert "cases solved by the general solver" in out
    _, _, listed = out.partition("failures by message:\n")
    assert listed.lstrip().startswith("2 x the line (# m) is not shorter"), out
