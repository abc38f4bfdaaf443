"""A system study's position sweep as a grid (:mod:`cablestudy.analyses.system_grid`): YAML to
netCDF through the CLI, against the same study run case by case
(:func:`cablestudy.study.cases.expand_cases`, each case through
:func:`cablestudy.analyses.system.evaluate_system_case`), chunk by chunk the same bits, and
the cases the compiled path does not take counted with their reason.

Tolerance against the case-by-case run: both converge the free points to the study's
1e-11 relative net force and then take one more Newton step, from different starts (the
template's equilibrium here, the study's positions there), so they agree to round-off
times the conditioning; 1e-9 relative to each variable's largest value is the issue's
bar for equal answers and catches any wrong term (an O(1) change). The Newton's own
iteration count and final residual depend on the start and are not compared.
"""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from cablestudy.analyses.static_grid import evaluate_grid_chunk
from cablestudy.analyses.system_grid import SystemGrid
from cablestudy.cli import main
from cablestudy.run.grid_runner import study_grid
from cablestudy.run.runner import run_study
from cablestudy.study import parse_study_text
from cablestudy.study.grid import expand_grid
from tests.integration.test_system_study import SYSTEM

#: a laid line between two anchors on the seabed: no compiled kernel takes a line with
#: both ends on the seabed, so every case goes to the general path (and still solves)
GROUND = SYSTEM.replace(
    "  clump:", "  anchor4: {kind: fixed, position: [-300.0, 150.0, -100.0]}\n  clump:"
).replace(
    "analysis:",
    "  ground: {a: anchor2, b: anchor4, segments: [{length: 105.0, diameter: 0.1, "
    "mass_per_length: 20.0, axial_stiffness: 5.0e8}]}\nanalysis:",
)
SKIP = {"static_iterations", "static_residual", "wall_time"}


def _run_cli(tmp, text: str, name: str) -> xr.Dataset:  # noqa: ANN001
    cfg = tmp / f"{name}.yaml"
    cfg.write_text(text)
    args = ["run", str(cfg), "--out", str(tmp), "--no-cache", "--no-progress"]
    assert main([*args, "--scheduler", "synchronous"]) == 0
    return xr.load_dataset(tmp / "sys.nc")


def _run_cases(tmp, text: str) -> xr.Dataset:  # noqa: ANN001
    src = parse_study_text(text, "sys.yaml")
    out = tmp / "cases"
    run_study(src, expand_grid(src), out, scheduler="synchronous", use_cache=False, progress=False)
    return xr.load_dataset(out / "sys.nc")


def _same(grid: xr.Dataset, cases: xr.Dataset) -> None:
    assert set(grid.variables) == set(cases.variables)
    for name in grid.variables:
        a, b = grid[name], cases[name]
        assert a.dims == b.dims and a.dtype == b.dtype, name
        if name in SKIP:
            continue
        if a.dtype.kind == "f":
            scale = max(float(np.nanmax(np.abs(b.values))), 1e-300)
            np.testing.assert_allclose(a.values, b.values, rtol=0, atol=1e-9 * scale, err_msg=name)
        else:
            assert np.array_equal(a.values, b.values), name


def test_position_sweep_runs_as_a_grid_and_equals_the_case_by_case_run(tmp_path) -> None:  # noqa: ANN001
    """Legs on the seabed to a clump (free), a bridle to the body, a leg to the body:
    the surge sweep through the CLI takes the grid, and every variable, dimension,
    coordinate and unit is that of the case-by-case run."""
    assert isinstance(study_grid(parse_study_text(SYSTEM, "sys.yaml")), SystemGrid)
    grid = _run_cli(tmp_path, SYSTEM, "sys")
    cases = _run_cases(tmp_path, SYSTEM)
    _same(grid, cases)
    assert grid.attrs["cases_fallback"] == 0 and grid.attrs["fallback_reasons"] == ""
    assert np.all(grid["status"].values == 0)
    assert np.all(grid["laid_length"].sel(line=["leg1", "leg2"]).values > 0.0)  # on the seabed
    for name in ("line", "point", "body", "dof", "dof_j", "s", "component"):
        assert np.array_equal(grid[name].values, cases[name].values), name
        assert grid[name].attrs == cases[name].attrs, name


def test_a_case_alone_equals_the_case_inside_the_sweep_bit_for_bit() -> None:
    """Each case starts from the template's equilibrium, never from another case: a
    chunk of one row, or of rows in another grouping, gives the same bits."""
    grid = study_grid(parse_study_text(SYSTEM, "sys.yaml"))
    whole = evaluate_grid_chunk(grid, 0, grid.shape[0])
    for lo, hi in ((4, 5), (0, 1), (2, 7), (8, 9)):
        part = evaluate_grid_chunk(grid, lo, hi)
        assert np.array_equal(part.status, whole.status[lo:hi])
        for name, values in whole.data.items():
            assert np.array_equal(part.data[name], values[lo:hi], equal_nan=True), name


def test_cases_the_compiled_path_does_not_take_are_counted_with_their_reason(tmp_path) -> None:  # noqa: ANN001
    """A line laid between two anchors: the general path solves each case, the dataset
    counts them (cases_fallback, fallback_reasons), each case carries the fallback
    warning, and the values are the case-by-case run's."""
    grid = _run_cli(tmp_path, GROUND, "ground")
    n = grid.sizes["surge"]
    assert grid.attrs["cases_fallback"] == n
    assert grid.attrs["fallback_reasons"] == (
        f"{n} x line ground has an end on or below the seabed that is not an anchor (a fixed "
        "point with the line's other end above the seabed)"
    )
    assert np.all(grid["status"].values == 0)
    assert all("fallback" in w for w in grid["warning"].values)
    cases = _run_cases(tmp_path, GROUND)
    for name in ("tension_a", "tension_b", "point_position", "body_force", "body_stiffness"):
        scale = float(np.nanmax(np.abs(cases[name].values)))
        np.testing.assert_allclose(grid[name].values, cases[name].values, atol=1e-9 * scale)


def test_load_and_anchor_sweeps_run_as_a_grid_and_equal_the_case_by_case_run(tmp_path) -> None:  # noqa: ANN001
    """The clump's mass and volume, a vertical force on it and an anchor's position, on
    two axes: the grid (each case from the template's equilibrium moved to first order
    with its loads and points) equals the case-by-case run."""
    text = SYSTEM.split("sweep:")[0].replace(
        "mass: 3000.0, volume: 0.2}", "mass: 3000.0, volume: 0.2, force: [0.0, 0.0, 0.0]}"
    ) + (
        "sweep:\n"
        "  zip:\n"
        "    - name: clump\n"
        "      points.clump.mass: [1000.0, 4000.0, 6000.0]\n"
        "      points.clump.volume: [0.1, 0.3, 0.2]\n"
        "    - name: pull\n"
        "      points.clump.force.2: [0.0, -2.0e4]\n"
        "      points.anchor3.position.0: [250.0, 240.0]\n"
    )
    assert isinstance(study_grid(parse_study_text(text, "sys.yaml")), SystemGrid)
    grid = _run_cli(tmp_path, text, "loads")
    assert grid.attrs["cases_fallback"] == 0 and np.all(grid["status"].values == 0)
    _same(grid, _run_cases(tmp_path, text))


@pytest.mark.parametrize(
    "sweep",
    [
        "  lines.bridle.segments.0.length: [69.0, 70.0]\n",  # a line's property
        "  bodies.buoy.position: [[0, 0, 0, 0, 0, 0], [1, 0, 0, 0, 0, 0]]\n",  # whole vector
    ],
)
def test_other_sweeps_run_case_by_case(sweep: str) -> None:
    text = SYSTEM.split("sweep:")[0] + "sweep:\n" + sweep
    assert not study_grid(parse_study_text(text, "sys.yaml")).chunked


def test_a_swept_anchor_below_the_seabed_leaves_the_grid_for_the_case_by_case_report() -> None:
    """Two axes moving one anchor over a seabed rising towards +x (1 degree): each value
    alone is valid, one combination lies below the seabed. The grid refuses the study
    and the report of the sweep's faults names the point."""
    from cablestudy.study.loader import StudyError

    text = (
        SYSTEM.split("sweep:")[0]
        .replace(
            "{fluid: water, depth: 100.0}",
            "{fluid: water, depth: 100.0, seabed: {slope_deg: 1.0, slope_heading_deg: 0.0}}",
        )
        .replace("[250.0, 0.0, -100.0]", "[0.0, 0.0, -90.0]")
        + "sweep:\n  points.anchor3.position.0: [0.0, 250.0]\n"
        + "  points.anchor3.position.2: [-90.0, -99.0]\n"
    )
    src = parse_study_text(text, "sys.yaml")
    with pytest.raises(StudyError, match="anchor3.position: the point lies below the seabed"):
        study_grid(src)


def test_surge_where_a_leg_touches_down_is_settled_by_the_compiled_path() -> None:
    """case8 around 14.35 m of surge, where a leg's touchdown point reaches its anchor:
    each line's branch (hanging free or on the seabed) is chosen by its ends' positions
    alone, so the net force on the junctions is a function of their positions and the
    line search settles every case (chosen by the line's state at the iterate, it
    jumped there, and these cases went to the general path)."""
    from pathlib import Path

    text = (Path(__file__).parents[2] / "configs" / "system-spread-bridles.yaml").read_text()
    text = text.replace(
        "{start: 0.0, stop: 10.0, num: 6, name: surge}",
        "{start: -14.36, stop: -14.34, num: 11, name: surge}",
    )
    grid = study_grid(parse_study_text(text, "case8.yaml"))
    assert isinstance(grid, SystemGrid)
    chunk = evaluate_grid_chunk(grid, 0, grid.shape[0])
    assert np.all(chunk.status == 0)
    assert list(chunk.fallback_reason) == [""] * 11


def test_strain_warning_in_the_grid_is_the_case_by_case_one(tmp_path) -> None:  # noqa: ANN001
    """analysis.static.strain_warning set low: the lines above it are named in each
    case's warning exactly as case by case."""
    text = SYSTEM.replace(
        "static: {nodes: 11, tolerance: 1.0e-11}",
        "static: {nodes: 11, tolerance: 1.0e-11, strain_warning: 1.0e-4}",
    )
    grid = _run_cli(tmp_path, text, "strain")
    assert any("strain" in w for w in grid["warning"].values)
    cases = _run_cases(tmp_path, text)
    assert list(grid["warning"].values) == list(cases["warning"].values)
