"""A quasi-static database whose grid crosses the taut chord (end distance = the line's
unstretched length, where the tension turns to rising with EA: a kink in every table)
through YAML -> cablestudy run -> <name>.database.nc -> cablestudy lookup: the build
flags the cells its bicubic patches cannot follow (cell_check), warns in the run summary
and the case's warning, and the lookup refuses a point in a flagged cell; a grid wholly
on the slack side has no flagged cell and looks up to the guide's accuracy
(docs/guide/cable-laws.md)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cablestudy.analyses.database import CELL_OFF, CELL_TAUT_CHORD, open_database
from cablestudy.cli import main
from cablestudy.study import load_study

from .test_database_radial import direct

# the guide's 120 m wire (EA 6e8 N) on a radial grid of 17 x 17 points
WIRE = """\
name: {name}
environment: {{fluid: water}}
line:
  segments:
    - {{length: 120.0, diameter: 0.05, mass_per_length: 10.0, axial_stiffness: 6.0e8}}
ends:
  a: {{kind: fixed, position: [0.0, 0.0, -200.0]}}
  b: {{kind: fixed, position: [110.0, 0.0, -195.0]}}
analysis:
  static: {{method: catenary, nodes: 21}}
  database:
    grid: radial
    distance: {{start: 100.0, stop: {stop}, num: 17}}
    angle_deg: {{start: -30.0, stop: 30.0, num: 17}}
"""


def _run(tmp_path: Path, name: str, stop: float) -> Path:
    cfg = tmp_path / f"{name}.yaml"
    cfg.write_text(WIRE.format(name=name, stop=stop))
    assert main(["run", str(cfg), "--out", str(tmp_path), "--no-cache"]) == 0
    return cfg


def test_grid_across_the_taut_chord_is_flagged_and_its_lookup_refused(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    _run(tmp_path, "across", 150.0)
    out = capsys.readouterr().out
    assert "quasi-static database:" in out and "cells flagged" in out
    assert "a lookup in a flagged cell is refused: keep the grid on one side" in out
    ds = xr.load_dataset(tmp_path / "across.database.nc")
    check = ds["cell_check"].values
    assert check.shape == (17, 17)
    assert np.all(check[-1, :] == -1) and np.all(check[:, -1] == -1)
    d = ds["distance"].values
    # the cells straddling 120 m (d 118.75 .. 121.875) and only those carry the chord bit
    taut = (check[:-1, :-1] & CELL_TAUT_CHORD) > 0
    straddle = (d[:-1] < 120.0) & (d[1:] > 120.0)
    np.testing.assert_array_equal(taut, np.broadcast_to(straddle[:, None], taut.shape))
    # the lookup's cell at (110 m, 5 m) is off a direct solve (the guide's wrong tension)
    i = int(np.searchsorted(d, np.hypot(110.0, 5.0))) - 1
    j = int(np.searchsorted(ds["angle"].values, np.arctan2(5.0, 110.0))) - 1
    assert check[i, j] & CELL_OFF
    st = xr.load_dataset(tmp_path / "across.nc")
    assert "quasi-static database: " in str(st["warning"].values)
    assert int(st["status"]) == 0  # the tables themselves are verified solves

    assert main(["lookup", str(tmp_path / "across.database.nc"), "--at", "110", "5"]) == 2
    err = capsys.readouterr().err
    assert "flagged cell" in err and "distance 109.375 .. 112.5 m" in err
    assert "one side of the taut chord" in err
    # the Python API too, and its opt-in returns the (wrong) patch value
    db = open_database(str(tmp_path / "across.database.nc"))
    with pytest.raises(ValueError, match="flagged cell"):
        db.lookup(110.0, 5.0)
    db.allow_flagged = True
    assert db.lookup(110.0, 5.0)["tension_a"] < 0.0  # the ringing the check caught


def test_grid_on_the_slack_side_is_verified_and_looks_up_to_the_guide_accuracy(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    cfg = _run(tmp_path, "slack", 118.0)
    assert "cells flagged" not in capsys.readouterr().out
    path = tmp_path / "slack.database.nc"
    assert np.all(xr.load_dataset(path)["cell_check"].values[:-1, :-1] == 0)
    study, _ = load_study(str(cfg))
    assert main(["lookup", str(path), "--at", "110", "5"]) == 0
    got = json.loads(capsys.readouterr().out)
    res = direct(study, 110.0, 5.0)
    scale = float(np.linalg.norm(res.force_a))
    # guide: 17 points a side, the h^4 error is ~7e-6 of the largest end tension of a
    # smooth radial table; the grid's largest end tension (near 118 m) is ~10x that at
    # (110, 5), so 1e-4 of the local tension bounds it with room for the cell position
    np.testing.assert_allclose(got["force_a"], res.force_a, rtol=0, atol=1e-4 * scale)
    np.testing.assert_allclose(got["force_b"], res.force_b, rtol=0, atol=1e-4 * scale)


def test_cli_allow_flagged_returns_the_value_with_a_warning(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """--allow-flagged: the patch value, said to be unverified in the JSON and on stderr."""
    _run(tmp_path, "opt", 150.0)
    capsys.readouterr()
    path = str(tmp_path / "opt.database.nc")
    assert main(["lookup", path, "--at", "110", "5", "--allow-flagged"]) == 0
    captured = capsys.readouterr()
    got = json.loads(captured.out)
    assert "distance 109.375 .. 112.5 m" in got["warning"] and "warning" in captured.err
    assert got["tension_a"] < 0.0
