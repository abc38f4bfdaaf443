"""A line above the water's surface, YAML -> netCDF through the command line: a lazy wave
whose buoyancy section arches out of the water keeps status 0 and its numbers, and its
``warning`` names the line and its highest node (z and s); the same line with a deeper
anchor stays under water and is not warned. Every static path: a sweep of end positions
run as arrays (catenary), case by case (shooting), one line alone, a system case and a
system sweep run as arrays.

The lazy wave: 360 m from an anchor (end A) to a fairlead 5 m down (end B), 250 m
away: 200 m of riser (60 kg/m, 0.2 m: 28 kg/m heavier than the water it displaces),
100 m of buoyancy section (0.6 m: 230 kg/m lighter) and 60 m of riser. With the anchor
150 m down the buoyancy lifts its section some 45 m out of the water; 220 m down the
taut line holds the hog bend's top about 1 m under the surface (its static shape gives
it, below).
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cablestudy.analyses.plausibility import SURFACE_TOLERANCE
from cablestudy.analyses.system_grid import SystemGrid
from cablestudy.cli import main
from cablestudy.run.grid_runner import study_grid
from cablestudy.study import parse_study_text

SEGMENTS = """\
      - {length: 200.0, diameter: 0.2, mass_per_length: 60.0, axial_stiffness: 1.0e9}
      - {length: 100.0, diameter: 0.6, mass_per_length: 60.0, axial_stiffness: 1.0e9}
      - {length: 60.0, diameter: 0.2, mass_per_length: 60.0, axial_stiffness: 1.0e9}
"""

LINE = f"""\
name: wave
environment: {{fluid: water}}
line:
  segments:
{SEGMENTS.replace("      -", "    -")}ends:
  a: {{kind: fixed, position: [0.0, 0.0, -150.0]}}
  b: {{kind: fixed, position: [250.0, 0.0, -5.0]}}
analysis:
  static: {{nodes: 73METHOD}}
sweep:
  ends.a.position.2: {{values: [-150.0, -220.0], name: anchor_z}}
"""

SYSTEM = f"""\
name: wave
environment: {{fluid: water}}
points:
  anchor: {{kind: fixed, position: [0.0, 0.0, -150.0]}}
  fair: {{kind: fixed, position: [250.0, 0.0, -5.0]}}
  anchor2: {{kind: fixed, position: [500.0, 0.0, -150.0]}}
lines:
  riser:
    a: anchor
    b: fair
    segments:
{SEGMENTS}  leg:
    a: fair
    b: anchor2
    segments: [{{length: 300.0, diameter: 0.2, mass_per_length: 60.0, axial_stiffness: 1.0e9}}]
analysis:
  static: {{nodes: 73}}
sweep:
  points.anchor.position.2: {{values: [-150.0, -220.0], name: anchor_z}}
"""

WARNING = re.compile(
    r"surface: (the line|line riser) rises above the water's surface \(z = 0\) to "
    r"z = (\S+) m at s = (\S+) m \(its highest node"
)


def _run(tmp_path: Path, text: str) -> tuple[xr.Dataset, str, int]:
    tmp_path.mkdir(parents=True, exist_ok=True)
    cfg = tmp_path / "wave.yaml"
    cfg.write_text(text)
    code = main(["run", str(cfg), "--out", str(tmp_path), "--scheduler", "synchronous"])
    return xr.load_dataset(tmp_path / "wave.nc"), cfg.read_text(), code


def _check(ds: xr.Dataset, line: str | None = None) -> None:
    """The shallow anchor's case warns with its own highest node; the deep one does not."""
    if line is not None:
        ds = ds.sel(line=line)
    assert ds["status"].values.tolist() == [0, 0]  # kept: a warning, not a failure
    shallow, deep = (ds.sel(anchor_z=v) for v in (-150.0, -220.0))
    match = WARNING.search(str(shallow["warning"].values))
    assert match, str(shallow["warning"].values)
    assert match.group(1) == ("the line" if line is None else f"line {line}")
    # the numbers are the dataset's own highest node, printed to 4 significant digits
    # (5e-4 relative): no second computation to disagree with
    k = int(shallow["z"].argmax("s"))
    z_top = float(shallow["z"][k])
    # arc length: the s coordinate where every case has the same (else per case)
    s_top = float((shallow["arc_length"] if "arc_length" in shallow else shallow["s"])[k])
    assert float(match.group(2)) == pytest.approx(z_top, rel=5e-4)
    assert float(match.group(3)) == pytest.approx(s_top, rel=5e-4)
    # out of the water by far more than any tolerance, on the buoyancy section (its top
    # is where the net upward load ends: within 200-300 m of the anchor)
    assert z_top > 10.0 and 200.0 <= s_top <= 300.0
    # the deep anchor: the hog bend's top is an interior maximum, under the surface
    assert str(deep["warning"].values) == ""
    z = deep["z"].values
    interior = int(np.argmax(z[1:-1])) + 1
    assert z[interior] > z[interior - 1] and z[interior] > z[interior + 1]  # a hog bend
    assert -5.0 < z[interior] < -SURFACE_TOLERANCE * 360.0  # near, but under, the surface


@pytest.mark.parametrize("method", ["", ", method: shooting"])
def test_a_lazy_wave_out_of_the_water_is_warned(tmp_path: Path, method: str) -> None:
    """The end-position sweep runs as arrays (analyses.static_grid): catenary through
    the compiled kernels, shooting through its solver per case (a case alone, through
    analyses.evaluate: test_one_line_alone_is_warned)."""
    text = LINE.replace("METHOD", method)
    grid = study_grid(parse_study_text(text, "wave.yaml"))
    assert grid is not None and grid.arrays  # the path named above
    ds, _, code = _run(tmp_path, text)
    assert code == 0
    _check(ds)
    assert int(ds.attrs["cases_warned"]) == 1


def test_one_line_alone_is_warned(tmp_path: Path) -> None:
    text = LINE.split("sweep:")[0]
    ds, _, code = _run(tmp_path, text.replace("METHOD", ""))
    assert code == 0 and int(ds["status"]) == 0
    match = WARNING.search(str(ds["warning"].values))
    assert match and float(match.group(2)) == pytest.approx(float(ds["z"].max()), rel=5e-4)


def test_the_same_line_in_air_is_not_judged(tmp_path: Path) -> None:
    """In air there is no surface: a line strung above z = 0 (a catenary between two
    supports 20 m up) is where it should be."""
    text = (
        LINE.split("sweep:")[0]
        .replace("fluid: water", "fluid: air")
        .replace("[0.0, 0.0, -150.0]", "[0.0, 0.0, 20.0]")
        .replace("[250.0, 0.0, -5.0]", "[300.0, 0.0, 20.0]")
        .replace("METHOD", "")
    )
    ds, _, code = _run(tmp_path, text)
    assert code == 0 and int(ds["status"]) == 0
    assert float(ds["z"].max()) == pytest.approx(20.0)  # held at the supports
    assert str(ds["warning"].values) == ""


def test_a_system_names_the_line_out_of_the_water(tmp_path: Path) -> None:
    """The anchor sweep of a system runs as arrays (analyses.system_grid); without the
    sweep, case by case (analyses.system). Only the lazy wave, riser, is named: leg hangs
    from the same fairlead 5 m down."""
    assert isinstance(study_grid(parse_study_text(SYSTEM, "wave.yaml")), SystemGrid)
    ds, _, code = _run(tmp_path, SYSTEM)
    assert code == 0
    _check(ds, "riser")
    assert "leg" not in str(ds["warning"].sel(anchor_z=-150.0).values)
    assert float(ds["z"].sel(line="leg").max()) == pytest.approx(-5.0, abs=1e-6)
    one, _, code = _run(tmp_path / "one", SYSTEM.split("sweep:")[0])
    assert code == 0
    match = WARNING.search(str(one["warning"].values))
    assert match and match.group(1) == "line riser"
    assert float(match.group(2)) == pytest.approx(float(one["z"].sel(line="riser").max()), rel=5e-4)
    assert math.isclose(
        float(match.group(2)), float(ds["z"].sel(line="riser", anchor_z=-150.0).max()), rel_tol=5e-4
    )


DYNAMIC = (
    LINE.split("sweep:")[0].replace("-150.0]", "-220.0]").replace("nodes: 73METHOD}", "nodes: 37}")
    + """\
  dynamic:
    excitation: {end: b, direction: [1.0, 0.0, 0.0], amplitude: 0.5, frequency: 0.05}
    method: METHOD
    elements: 36HISTORY
sweep:
  analysis.dynamic.excitation.amplitude: [0.5, 4.0]
"""
)


def test_motion_out_of_the_water_is_warned(tmp_path: Path) -> None:
    """The deep anchor's lazy wave (statics: its top about 1 m under the surface) surged
    at its fairlead: 0.5 m keeps it under water, 4 m throws the buoyancy section out.
    Judged on the elevation envelope ``z_envelope_max`` (every step's node maxima over
    the steady window), which the warning cites; with the whole line's history kept, the
    envelope holds the history's highest point (resampled from the same steps, linear
    between them: it cannot rise above the steps' maxima, so the bound is the steady
    state's period-to-period change; measured: the envelope lies 0 and 1.4 cm above the
    history's highest point, the history's 32 samples a period missing the steps' peak)."""
    history = "\n    history: {whole_line: true, samples_per_period: 32}"
    text = DYNAMIC.replace("METHOD", "time").replace("HISTORY", history)
    ds, _, code = _run(tmp_path, text)
    assert code == 0 and ds["status"].values.tolist() == [0, 0]
    assert -5.0 < float(ds["z"].isel(amplitude=0).max()) < 0.0  # statics: just under
    envelope = ds["z_envelope_max"].max("s")
    z_hist = ds["history_line_position"].sel(component="z").max(["time", "s"])
    assert np.all(envelope.values >= z_hist.values - 1e-2)
    calm, rough = (str(w) for w in ds["warning"].values)
    assert calm == "" and float(envelope.isel(amplitude=0)) < 0.0
    match = WARNING.search(rough)
    assert match and "over the motion" in rough
    assert float(match.group(2)) == pytest.approx(float(envelope.isel(amplitude=1)), rel=5e-4)
    assert float(match.group(2)) > 0.0


def test_the_frequency_domain_judges_its_own_envelope(tmp_path: Path) -> None:
    """``method: frequency`` gives the same variable (each node's static elevation plus
    its heave amplitude) and the same warning. Against the time domain: each method's
    rise over its own envelope at 1 mm (the time domain's discrete model hangs up to
    7 cm off the static shape at these 10 m elements; the frequency domain's model sits
    on it) agrees at 0.5 m within 5 % of the surge amplitude, the order of the
    linearisation's error on this lazy wave (measured: 8 mm, 1.6 %; 3.2 mm at 0.1 m)."""
    text = DYNAMIC.replace("HISTORY", "").replace("[0.5, 4.0]", "[0.001, 0.5, 4.0]")
    runs = {m: _run(tmp_path / m, text.replace("METHOD", m))[0] for m in ("time", "frequency")}
    rise = {}
    for m, ds in runs.items():
        tiny, calm, rough = (str(w) for w in ds["warning"].values)
        # at 1 mm the time domain's per-period extremes wander by ~5 % of the 9 N range
        # even after 2000 periods (measured: 8.56 N at 80, 9.02 N at 2000; the quadratic
        # drag hardly damps a 1 mm motion): its steady-state test, judged against the
        # range (dynamics/steady.py), says so; no surface warning either way
        assert tiny == "" or tiny.startswith("unsettled: no steady state")
        assert calm == "" and "over the motion" in rough
        env = ds["z_envelope_max"]
        rise[m] = env.isel(amplitude=1) - env.isel(amplitude=0)
    assert float(np.abs(rise["time"] - rise["frequency"]).max()) < 0.05 * 0.5


@pytest.mark.parametrize("method", ["time", "frequency"])
def test_a_system_in_motion_names_the_line_out_of_the_water(tmp_path: Path, method: str) -> None:
    """The system with the deep anchor, its fairlead surged: the riser's elevation
    envelope (lines, s) is the one line's by the same method (the fairlead's motion is
    prescribed, so the leg hanging from it does not move the riser; not bit for bit: the
    time domain's step control is shared by both lines, measured 1.0e-6 m, the Newton
    tolerance's order; the frequency domain's drag iteration runs over the system,
    7.3e-8 m; bar 1e-4 m), and the warning names the riser over the motion at 4 m, none
    at 0.5 m."""
    motion = """\
  dynamic:
    excitation: {point: fair, direction: [1.0, 0.0, 0.0], amplitude: 0.5, frequency: 0.05}
    method: METHOD
    elements: 36
sweep:
  analysis.dynamic.excitation.amplitude: [0.5, 4.0]
"""
    motion = motion.replace("METHOD", method)
    text = SYSTEM.split("sweep:")[0].replace("-150.0]", "-220.0]", 1).replace("73}", "37}")
    ds, _, code = _run(tmp_path, text + motion)
    assert code == 0 and ds["status"].values.tolist() == [0, 0]
    calm, rough = (str(w) for w in ds["warning"].values)
    assert calm == ""
    match = WARNING.search(rough)
    assert match and match.group(1) == "line riser" and "over the motion" in rough
    riser = ds["z_envelope_max"].sel(line="riser")
    assert float(match.group(2)) == pytest.approx(float(riser.isel(amplitude=1).max()), rel=5e-4)
    one = _run(tmp_path / "one", DYNAMIC.replace("METHOD", method).replace("HISTORY", ""))[0]
    assert float(np.abs(riser.values - one["z_envelope_max"].values).max()) < 1e-4
