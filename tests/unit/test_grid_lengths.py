"""Static sweeps of where the line's parts lie as arrays (cablestudy.study.grid_lines'
LINE_GEOMETRY): a segment's unstretched length, an attachment's position along the line
and its force components, swept with end positions.

The grid builds one line per combination of those values (the template with them copied
in, every combined check of the models run), cuts each into its pieces as a case alone
is, and the compiled kernels take the cases as arrays; the dataset must be the
case-by-case one bit for bit (the same functions build the same numbers: no tolerance).
A combination the full validation refuses (an attachment beyond a swept line's end) is
refused before any work, named at its line. A length sweep of a hanging line matches the
closed-form elastic catenary at each length."""

from __future__ import annotations

from collections import OrderedDict
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from scipy.optimize import root

from cablestudy.analyses import static as static_analysis
from cablestudy.analyses.variables import KEPT_STATUSES
from cablestudy.run.runner import run_study
from cablestudy.study import parse_study_text
from cablestudy.study.grid import expand_grid
from cablestudy.study.grid_lines import line_studies
from cablestudy.study.loader import StudyError
from tests.grid_bits import same_bits

#: a chain and a wire anchored on the seabed at A (the contact kernel), the chain's
#: length swept with the fairlead's offset
LENGTH = """\
name: gl
environment: {fluid: water, depth: 30.0, seabed: {friction: 0.5}}
line:
  segments:
    - {length: 60.0, diameter: 0.05, weight_in_fluid: 60.0, axial_stiffness: 2.0e8}
    - {length: 40.0, diameter: 0.02, mass_per_length: 2.466, axial_stiffness: 6.283e7}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -30.0]}
  b: {kind: fixed, position: [92.5, 0.0, -8.6]}
analysis:
  static: {nodes: 21}
sweep:
  ends.b.position.0: {start: 84.0, stop: 96.0, num: 5, name: span}
  line.segments.0.length: [50.0, 60.0, 70.0]
"""
#: a clump weight whose position is swept across the joint of the two segments (at
#: 60 m: a line cut into fewer pieces there) and beyond, lines hanging free
CLUMP = (
    LENGTH.replace("depth: 30.0, seabed: {friction: 0.5}", "depth: 50.0")
    .replace("[0.0, 0.0, -30.0]", "[0.0, 0.0, -10.0]")
    .replace("ends:\n", "  attachments:\n    - {s: 50.0, mass: 300.0}\nends:\n")
    .replace(
        "line.segments.0.length: [50.0, 60.0, 70.0]", "line.attachments.0.s: [20.0, 60.0, 85.0]"
    )
    .replace("{start: 84.0, stop: 96.0, num: 5, name: span}", "{start: 70.0, stop: 96.0, num: 5}")
)
#: a point force (a towing pull, a buoy's net lift) whose components are swept, on a line
#: anchored at end B (the contact kernel on the reversed line), its position swept too
FORCE = (
    LENGTH.replace("[0.0, 0.0, -30.0]", "[0.0, 0.0, -12.0]")
    .replace("[92.5, 0.0, -8.6]", "[92.5, 0.0, -30.0]")
    .replace("ends:\n", "  attachments:\n    - {s: 30.0, force: [0.0, 0.0, 200.0]}\nends:\n")
    .replace(
        "line.segments.0.length: [50.0, 60.0, 70.0]",
        "line.attachments.0.force.2: [0.0, 400.0]\n  line.attachments.0.force.0: [-100.0, 100.0]"
        "\n  line.attachments.0.s: [10.0, 55.0]",
    )
)


@pytest.fixture(autouse=True)
def _fresh_static_cache(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(static_analysis, "_STATIC_CACHE", OrderedDict())


@pytest.mark.parametrize("text", [LENGTH, CLUMP, FORCE], ids=["length", "clump", "force"])
def test_swept_lengths_and_attachments_run_as_arrays_with_the_case_datasets_bits(
    tmp_path: Path, text: str
) -> None:
    src = parse_study_text(text, "gl.yaml")
    grid = expand_grid(src)
    assert grid.chunked and grid.arrays  # the compiled array route, not case by case
    n_lines = grid.size // grid.shape[0]  # one line per combination of its values
    assert len(line_studies(grid)) == n_lines
    fast = xr.load_dataset(
        run_study(src, grid, tmp_path / "g", scheduler="synchronous", use_cache=False).path
    )
    slow = xr.load_dataset(  # every case as a validated study, through evaluate_case
        run_study(
            src, replace(grid, chunked=False), tmp_path / "c", scheduler="synchronous",
            use_cache=False,
        ).path
    )  # fmt: skip
    kept = np.isin(slow["status"].values, KEPT_STATUSES)
    assert int(kept.sum()) >= kept.size // 2  # most cases solve: the equality means something
    if text is not CLUMP:
        assert float(slow["laid_length"].max()) > 0.0  # the contact kernel did run
    t = slow["tension_a"].values.reshape(grid.shape[0], -1)
    assert np.nanmax(np.nanstd(t, axis=1)) > 0.0  # the swept values change the answer
    if text is LENGTH:  # each case's nodes along its own line
        ends = slow["arc_length"].isel(s=-1).values
        assert np.array_equal(ends[-1], np.array([90.0, 100.0, 110.0]))  # the widest span
    same_bits(fast, slow)


def test_an_attachment_beyond_a_swept_lines_end_is_refused_before_any_work() -> None:
    # the clump at 85 m is on the 60 + 40 m line, not on the 60 + 20 m one: each value
    # valid alone, refused together, named at its line with the value
    beyond = CLUMP.replace(
        "line.attachments.0.s: [20.0, 60.0, 85.0]", "line.attachments.0.s: [85.0]"
    )
    beyond = beyond.replace(
        "ends.b.position.0: {start: 70.0, stop: 96.0, num: 5}",
        "ends.b.position.0: [80.0]\n  line.segments.1.length: [40.0, 20.0]",
    )
    with pytest.raises(StudyError) as exc:
        expand_grid(parse_study_text(beyond, "gl.yaml"))
    text = str(exc.value)
    assert "line.attachments.0.s" in text and "beyond the end of the line" in text, text
    assert "85" in text and "sweep case" in text, text
    # a weightless line whose swept length reaches its chord: refused per line length
    light = (
        LENGTH.replace("{fluid: water, depth: 30.0, seabed: {friction: 0.5}}", "{fluid: vacuum}")
        .replace("weight_in_fluid: 60.0", "weight_in_fluid: 0.0")
        .replace("mass_per_length: 2.466", "weight_in_fluid: 0.0")
        .replace("[0.0, 0.0, -30.0]", "[0.0, 0.0, 0.0]")
        .replace("[92.5, 0.0, -8.6]", "[105.0, 0.0, 0.0]")
        .replace("{start: 84.0, stop: 96.0, num: 5, name: span}", "[105.0]")
    )
    assert expand_grid(parse_study_text(light.replace("70.0]", "64.0]"), "gl.yaml")).arrays
    with pytest.raises(StudyError, match="no weight in the fluid"):
        expand_grid(parse_study_text(light, "gl.yaml"))  # 70 + 40 m > 105 m


def _elastic_catenary(length: float, w: float, ea: float, dx: float, dz: float) -> np.ndarray:
    """(H, V_A) of a uniform elastic catenary from A to B = A + (dx, dz): the tension
    vector T(s) = (H, V_A + w s) (the pull of the part beyond s), in closed form
    (Irvine's elastic catenary) solved to round-off."""

    def ends(p: np.ndarray) -> np.ndarray:
        h, va = p
        vb = va + w * length
        x = h * length / ea + h / w * (np.arcsinh(vb / h) - np.arcsinh(va / h))
        z = (va * length + 0.5 * w * length**2) / ea + h / w * (
            np.hypot(1, vb / h) - np.hypot(1, va / h)
        )
        return np.array([x - dx, z - dz])

    guess = np.array([w * length, -0.5 * w * length])
    sol = root(ends, guess, method="hybr", tol=1e-14)
    assert np.max(np.abs(ends(sol.x))) < 1e-11 * length  # round-off of the ends' sums
    return sol.x


def test_a_length_sweep_of_a_hanging_line_is_the_elastic_catenary_at_each_length(
    tmp_path: Path,
) -> None:
    """YAML -> netCDF through the CLI, the method left out: a steel wire between supports
    at different levels in air, its length swept; the end tensions at each length are the
    closed form's."""
    from cablestudy import cli

    w, ea, dx, dz = 20.0, 2.0e6, 90.0, -8.0
    lengths = [95.0, 100.0, 110.0, 125.0]
    text = f"""\
name: hang
environment: {{fluid: air, gravity: 9.80665}}
line:
  segments:
    - {{length: 100.0, diameter: 0.02, weight_in_fluid: {w}, axial_stiffness: {ea}}}
ends:
  a: {{kind: fixed, position: [0.0, 0.0, 0.0]}}
  b: {{kind: fixed, position: [{dx}, 0.0, {dz}]}}
analysis:
  static: {{nodes: 11}}
sweep:
  line.segments.0.length: {lengths}
"""
    path = tmp_path / "hang.yaml"
    path.write_text(text)
    _, _, grid = cli._load(str(path))
    assert grid.arrays
    assert cli.main(["run", str(path), "--out", str(tmp_path / "out"), "--no-cache"]) == 0
    with xr.open_dataset(tmp_path / "out" / "hang.nc") as ds:
        assert int((ds["status"] == 0).sum()) == len(lengths) and ds.attrs["cases_fallback"] == 0
        for i, length in enumerate(lengths):
            h, va = _elastic_catenary(length, w, ea, dx, dz)
            case = ds.isel(length=i)
            assert float(case["arc_length"].isel(s=-1)) == length
            # the solver stops when the ends are within tolerance 1e-9 of the line's
            # length; with end tensions of 1-10 kN whose change per metre of end offset
            # is at most EA / L ~ 2e4 N/m, that is at most 1e-7 m * 2e4 N/m = 2e-3 N,
            # about 1e-6 of the smallest tension: bound at 1e-6 relative
            ta, tb = np.hypot(h, va), np.hypot(h, va + w * length)
            assert abs(float(case["tension_a"]) - ta) <= 1e-6 * ta
            assert abs(float(case["tension_b"]) - tb) <= 1e-6 * tb
            # the force on the support at A pulls it towards B and down the sag
            fa = case["force_a"].values
            assert abs(fa[0] - h) <= 1e-6 * ta and abs(fa[2] - va) <= 1e-6 * ta


#: a towed line: end A fixed, a known force at end B, its components swept
TOWED = """\
name: tow
environment: {fluid: water, depth: 200.0}
line:
  segments:
    - {length: 60.0, diameter: 0.05, weight_in_fluid: 60.0, axial_stiffness: 2.0e8}
    - {length: 40.0, diameter: 0.02, mass_per_length: 2.466, axial_stiffness: 6.283e7}
  attachments:
    - {s: 70.0, mass: 50.0}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -10.0]}
  b: {kind: force, force: [5000.0, 0.0, 2000.0]}
analysis:
  static: {nodes: 21}
sweep:
  ends.b.force.0: [1000.0, 5000.0, 20000.0]
  ends.b.force.2: [0.0, 3000.0, 8000.0]
  line.segments.1.length: [30.0, 40.0]
"""
#: a mooring leg: the horizontal pull and the height of end B known, swept
MOORED = (
    TOWED.replace("depth: 200.0", "depth: 60.0, seabed: {friction: 0.5}")
    .replace("[0.0, 0.0, -10.0]", "[0.0, 0.0, -60.0]")
    .replace(
        "{kind: force, force: [5000.0, 0.0, 2000.0]}",
        "{kind: mooring, force: [5000.0, 0.0], z: -5.0}",
    )
    .replace("ends.b.force.2: [0.0, 3000.0, 8000.0]", "ends.b.z: [-20.0, -5.0]")
)


@pytest.mark.parametrize("text", [TOWED, MOORED], ids=["force", "mooring"])
def test_swept_end_loads_run_as_arrays_with_the_case_datasets_bits(
    tmp_path: Path, text: str
) -> None:
    src = parse_study_text(text, "tow.yaml")
    grid = expand_grid(src)
    assert grid.chunked and grid.arrays
    fast = xr.load_dataset(
        run_study(src, grid, tmp_path / "g", scheduler="synchronous", use_cache=False).path
    )
    slow = xr.load_dataset(
        run_study(
            src, replace(grid, chunked=False), tmp_path / "c", scheduler="synchronous",
            use_cache=False,
        ).path
    )  # fmt: skip
    assert int((slow["status"] == 0).sum()) >= slow["status"].size // 2
    # the end's known load is what the line gets at B: force_b (the line's force on what
    # holds end B) is its opposite, to the solver's tolerance 1e-9 of the largest force
    ok = slow["status"] == 0
    fb = slow["force_b"].where(ok)
    scale = 1e-8 * float(np.abs(fb).max())
    assert np.nanmax(np.abs(fb.sel(component="x") + slow["force_0"])) <= scale
    if text is TOWED:
        assert np.nanmax(np.abs(fb.sel(component="z") + slow["force_2"])) <= scale
    else:  # end B at its known height
        z_b = slow["z"].where(ok).isel(s=-1)
        assert np.nanmax(np.abs(z_b - slow["b_z"])) <= 1e-8 * 60.0
    same_bits(fast, slow)
    # a mooring end swept below the seabed is refused before any work, named
    if text is MOORED:
        below = text.replace("ends.b.z: [-20.0, -5.0]", "ends.b.z: [-20.0, -70.0]")
        with pytest.raises(StudyError, match="below the seabed"):
            expand_grid(parse_study_text(below, "tow.yaml"))
