"""Static sweeps of a line's loads and of the seabed as arrays (cablestudy.study.grid_lines):
segment mass, weight in the fluid and diameter, attachment mass and volume, seabed slope
and friction, swept with end positions.

The grid builds one line per combination of those values (the template with them copied
in, every combined check of the models run) and the compiled kernels take the cases as
arrays; the dataset must be the case-by-case one bit for bit (the same functions build
the same numbers: no tolerance), and a combination the full validation refuses is
refused before any work, named at its line."""

from __future__ import annotations

from collections import OrderedDict
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cablestudy.analyses import static as static_analysis
from cablestudy.analyses.variables import KEPT_STATUSES
from cablestudy.run.runner import run_study
from cablestudy.study import parse_study_text
from cablestudy.study.grid import expand_grid
from cablestudy.study.grid_lines import line_studies
from cablestudy.study.loader import StudyError
from tests.grid_bits import same_bits

TEXT = """\
name: gl
environment: {fluid: water, depth: 50.0}
line:
  segments:
    - {length: 60.0, diameter: 0.02, mass_per_length: 2.466, axial_stiffness: 6.283e7}
    - {length: 40.0, diameter: 0.05, mass_per_length: 8.0, axial_stiffness: 2.0e8}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -10.0]}
  b: {kind: fixed, position: [92.5, 0.0, -8.6]}
analysis:
  static: {nodes: 21}
sweep:
  ends.b.position.0: {start: 60.0, stop: 100.5, num: 7, name: span}
  line.segments.0.mass_per_length: [1.0, 2.466, 6.0]
  line.segments.1.diameter: [0.05, 0.1]
"""
#: a buoy and a clump on the line: the attachment's mass and volume swept
ATTACHED = (
    TEXT.replace("ends:\n", "  attachments:\n    - {s: 50.0, mass: 100.0, volume: 0.05}\nends:\n")
    .replace(
        "line.segments.0.mass_per_length: [1.0, 2.466, 6.0]",
        "line.attachments.0.mass: [0.0, 400.0]",
    )
    .replace("line.segments.1.diameter: [0.05, 0.1]", "line.attachments.0.volume: [0.0, 0.3]")
)
#: anchored at end B on the seabed (the contact kernel on the reversed line), weights
#: given in the fluid
SEABED_B = (
    TEXT.replace("depth: 50.0", "depth: 30.0, seabed: {friction: 0.5}")
    .replace("[0.0, 0.0, -10.0]", "[0.0, 0.0, -12.0]")
    .replace("[92.5, 0.0, -8.6]", "[92.5, 0.0, -30.0]")
    .replace("mass_per_length: 8.0", "weight_in_fluid: 60.0")
    .replace("{start: 60.0, stop: 100.5, num: 7, name: span}", "{start: 88.0, stop: 100.0, num: 7}")
    .replace(
        "line.segments.1.diameter: [0.05, 0.1]", "line.segments.1.weight_in_fluid: [30.0, 120.0]"
    )
)

#: end A anchored on a seabed whose slope and friction are swept: the compiled contact
#: kernel per group of cases on one seabed
SLOPED = (
    TEXT.replace("depth: 50.0", "depth: 30.0, seabed: {friction: 0.5}")
    .replace("[0.0, 0.0, -10.0]", "[0.0, 0.0, -30.0]")
    .replace("{start: 60.0, stop: 100.5, num: 7, name: span}", "{start: 88.0, stop: 100.0, num: 7}")
    .replace(
        "line.segments.0.mass_per_length: [1.0, 2.466, 6.0]",
        "environment.seabed.slope_deg: [0.0, 1.0, 2.0]",
    )
    .replace("line.segments.1.diameter: [0.05, 0.1]", "environment.seabed.friction: [0.0, 0.5]")
)


@pytest.fixture(autouse=True)
def _fresh_static_cache(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(static_analysis, "_STATIC_CACHE", OrderedDict())


@pytest.mark.parametrize(
    "text", [TEXT, ATTACHED, SEABED_B, SLOPED], ids=["segments", "buoy", "seabed-b", "slope"]
)
def test_swept_loads_run_as_arrays_with_the_case_datasets_bits(tmp_path: Path, text: str) -> None:
    src = parse_study_text(text, "gl.yaml")
    grid = expand_grid(src)
    assert grid.chunked and grid.arrays  # the compiled array route, not case by case
    # one line per combination of the load values only (not per case)
    n_lines = grid.size // grid.shape[0]
    assert len(line_studies(grid)) == n_lines
    fast = xr.load_dataset(
        run_study(src, grid, tmp_path / "g", scheduler="synchronous", use_cache=False).path
    )
    slow = xr.load_dataset(  # every case as a validated study, through evaluate_case
        run_study(
            src,
            replace(grid, chunked=False),
            tmp_path / "c",
            scheduler="synchronous",
            use_cache=False,
        ).path
    )
    kept = np.isin(slow["status"].values, KEPT_STATUSES)
    assert int(kept.sum()) >= kept.size // 2  # most cases solve: the equality means something
    if text in (SEABED_B, SLOPED):
        assert float(slow["laid_length"].max()) > 0.0  # the contact kernel did run
    # the loads do change the answer (else the sweep would prove nothing)
    t = slow["tension_a"].values.reshape(grid.shape[0], -1)
    assert np.nanmax(np.nanstd(t, axis=1)) > 0.0
    same_bits(fast, slow)


def test_combinations_of_loads_are_refused_as_a_full_validation_refuses_them() -> None:
    # each weight in the fluid and each diameter valid alone; the most buoyant weight
    # with the largest diameter gives a negative mass (Study._physical), only together
    negative = (
        TEXT.replace("mass_per_length: 2.466", "weight_in_fluid: 10.0")
        .replace(
            "line.segments.0.mass_per_length: [1.0, 2.466, 6.0]",
            "line.segments.0.weight_in_fluid: [10.0, -50.0]",
        )
        .replace("line.segments.1.diameter: [0.05, 0.1]", "line.segments.0.diameter: [0.02, 0.1]")
    )
    with pytest.raises(StudyError) as exc:
        expand_grid(parse_study_text(negative, "gl.yaml"))
    assert "line.segments.0" in str(exc.value) and "sweep case" in str(exc.value), str(exc.value)
    # a line without weight in a vacuum between ends closer than its length: each
    # value valid alone (a weightless line with end B at 101 m, a span of 92.5 m with
    # weight), refused together by the chord check (per line over the grid)
    weightless = (
        TEXT.replace("{fluid: water, depth: 50.0}", "{fluid: vacuum}")
        .replace("mass_per_length: 2.466", "weight_in_fluid: 5.0")
        .replace("mass_per_length: 8.0", "weight_in_fluid: 0.0")
        .replace("[92.5, 0.0, -8.6]", "[101.0, 0.0, -8.6]")
        .replace("{start: 60.0, stop: 100.5, num: 7, name: span}", "[92.5, 101.0]")
        .replace(
            "line.segments.0.mass_per_length: [1.0, 2.466, 6.0]",
            "line.segments.0.weight_in_fluid: [0.0, 5.0]",
        )
        .replace("line.segments.1.diameter: [0.05, 0.1]", "line.segments.1.diameter: [0.05]")
    )
    with pytest.raises(StudyError, match="no weight in the fluid"):
        expand_grid(parse_study_text(weightless, "gl.yaml"))
    # spans beyond the line's length: every case is valid, and run as arrays
    taut = weightless.replace("[92.5, 101.0]", "[100.5, 101.0]")
    assert expand_grid(parse_study_text(taut, "gl.yaml")).arrays


def test_a_swept_mass_runs_from_the_study_file_as_arrays(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """YAML -> netCDF through the CLI, the method left out: the grid is the array one,
    and the tension at end A grows with the swept mass at every span (a heavier line
    between the same ends pulls harder: T_A rises monotonically with w for a catenary)."""
    from cablestudy import cli

    path = tmp_path / "gl.yaml"
    path.write_text(TEXT)
    _, _, grid = cli._load(str(path))
    assert grid.arrays
    assert cli.main(["run", str(path), "--out", str(tmp_path / "out")]) == 0
    assert "general solver" not in capsys.readouterr().out
    with xr.open_dataset(tmp_path / "out" / "gl.nc") as ds:
        assert int((ds["status"] == 0).sum()) == ds["status"].size
        assert ds.attrs["cases_fallback"] == 0
        t = ds["tension_a"].transpose("span", ...).values  # (span, mass, diameter)
        assert np.all(np.diff(t, axis=1) > 0.0)
