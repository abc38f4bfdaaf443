"""Warnings users see (issue 21, item 4), YAML -> netCDF through the command line: results
that are kept with status 0 but are implausible (strain above
``analysis.static.strain_warning``) or risky (slack, an unsettled time-domain run, a
batched-kernel fallback) carry a per-case ``warning``, the dataset counts them in
``cases_warned``, and the run ends with them grouped by kind."""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cablestudy.cli import main

#: a 550 m wire (EA 3.3e8 N) from an anchor 200 m down to a fairlead 10 m down, at three
#: horizontal distances: 300 m (slack: the line lies on the seabed beyond what its ends
#: fix: a failure), 500 m (a catenary) and 600 m (chord 629.3 m: stretched 14.4 %)
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
  static: {method: METHOD, nodes: 51STRAIN}
sweep:
  ends.b.position.0: {values: [500.0, 600.0], name: distance}
"""


def _wire(tmp_path: Path, method: str, strain: str = "") -> Path:
    cfg = tmp_path / f"wire-{method}.yaml"
    cfg.write_text(WIRE.replace("METHOD", method).replace("STRAIN", strain))
    return cfg


def _run(cfg: Path, out: Path, capsys: pytest.CaptureFixture[str]) -> tuple[xr.Dataset, str]:
    code = main(["run", str(cfg), "--out", str(out), "--scheduler", "synchronous"])
    printed = capsys.readouterr().out
    assert code == 0
    name = cfg.read_text().split("\n", 1)[0].split(": ")[1]
    return xr.load_dataset(out / f"{name}.nc"), printed


@pytest.mark.parametrize("method", ["catenary", "analytic"])
def test_a_wire_stretched_beyond_the_plausible_is_warned_not_failed(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], method: str
) -> None:
    """The 600 m case stretches the wire by about chord / length - 1 = 14.4 %, well above
    the default limit of 5 %: status 0, its numbers kept, and a warning naming the strain.
    Method catenary runs the sweep as arrays (cablestudy.analyses.static_grid), analytic case by
    case."""
    ds, printed = _run(_wire(tmp_path, method), tmp_path / "out", capsys)
    assert ds["status"].values.tolist() == [0, 0]
    assert ds["warning"].attrs["units"] == "1"
    assert "implausible or risky" in ds["warning"].attrs["long_name"]
    near, far = (str(w) for w in ds["warning"].values)
    assert "strain" not in near
    match = re.match(r"strain: largest strain (\S+) above the plausibility limit 0.05 ", far)
    assert match, far
    # closed form: the line is nearly straight (its weight, 3e5 N over the span, is
    # 0.6 % of the 4.8e7 N tension, so the sag shortens the chord by (wL/T)^2/24 ~ 2e-6
    # relative); the strain is then chord / length - 1 to that, and the warning prints 4
    # significant digits (5e-4 relative)
    chord = math.hypot(600.0, 180.0)
    assert float(match.group(1)) == pytest.approx(chord / 550.0 - 1.0, rel=1e-3)
    # the same strain as the dataset's own end tension over EA
    t_max = float(ds["tension"].sel(distance=600.0).max())
    assert float(match.group(1)) == pytest.approx(t_max / 3.3e8, rel=1e-3)
    assert isinstance(ds.attrs["cases_warned"], np.integer)
    assert int(ds.attrs["cases_warned"]) == sum(1 for w in ds["warning"].values if w)
    assert "warnings by kind (the cases keep status 0):" in printed
    assert re.search(r"\n +1 x strain, e\.g\.:\n +distance=600: strain: ", printed), printed
    # the warnings are kept in the cache with the cases: a re-run reuses both
    again, printed = _run(_wire(tmp_path, method), tmp_path / "out", capsys)
    assert "(0 computed, 2 reused from cache)" in printed
    assert again["warning"].values.tolist() == ds["warning"].values.tolist()
    assert re.search(r"\n +1 x strain, e\.g\.:\n", printed), printed


def test_the_strain_limit_is_the_studys_own(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """At a limit of 0.2 the 14.4 % case passes; at 0.01 the 500 m catenary (T / EA of
    about 4e-4) still passes and the 600 m case is warned against 0.01."""
    loose, printed = _run(_wire(tmp_path, "analytic", ", strain_warning: 0.2"), tmp_path, capsys)
    assert loose["warning"].values.tolist() == ["", ""]
    assert int(loose.attrs["cases_warned"]) == 0
    assert "warnings by kind" not in printed
    tight, _ = _run(_wire(tmp_path, "analytic", ", strain_warning: 0.01"), tmp_path, capsys)
    assert tight["warning"].values[0] == ""
    assert "above the plausibility limit 0.01 " in str(tight["warning"].values[1])


@pytest.mark.parametrize("value", ["0.0", "-0.05", "20.0", ".nan"])
def test_a_strain_limit_out_of_range_is_refused_naming_the_key(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], value: str
) -> None:
    cfg = _wire(tmp_path, "analytic", f", strain_warning: {value}")
    assert main(["validate", str(cfg)]) == 2
    err = capsys.readouterr().err
    assert "analysis.static.strain_warning" in err


#: a taut 10.98 m cable (Moustafa's) heaved at its end B at 1 Hz by 5 mm, 0.5 m and 1 m:
#: the small motion stays taut, the large ones go slack (the time domain's tension is
#: tension-only), and the largest does not settle within 12 periods
HEAVE = """\
name: heave
environment: {fluid: water}
line:
  segments:
    - {length: 10.9774, diameter: 0.01, mass_per_length: 0.61, axial_stiffness: 7.854e+6,
       drag_normal: 1.2, drag_tangential: 0.01, added_mass_normal: 1.0}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [10.792, 0.0, 0.0]}
analysis:
  static: {method: analytic, nodes: 21}
  dynamic:
    excitation: {end: b, direction: [0.0, 0.0, 1.0], amplitude: 0.01, frequency: 1.0}
    method: time
    elements: 20
    max_periods: 12
sweep:
  analysis.dynamic.excitation.amplitude: [0.005, 0.5, 1.0]
"""


def test_a_heave_sweep_reaching_slack_and_max_periods_is_warned(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    cfg = tmp_path / "heave.yaml"
    cfg.write_text(HEAVE)
    ds, printed = _run(cfg, tmp_path, capsys)
    assert ds["status"].values.tolist() == [0, 0, 0]
    warnings = [str(w) for w in ds["warning"].values]
    # slack where, and only where, the tension envelope along the line reaches zero
    slack = (ds["tension_envelope_min"].min("s") <= 0.0) | (ds["tension_min"] <= 0.0)
    assert ["slack: " in w for w in warnings] == slack.values.tolist()
    assert slack.values.tolist() == [False, True, True]
    # the line hangs from the surface (z = 0): the large heaves lift the stretch by end B
    # out of the water (its held end, moved as given, is not judged: the 5 mm heave is not
    # warned); the envelope's free nodes say where
    free = ds["z_envelope_max"].isel(s=slice(1, -1)).max("s")
    assert ["surface: " in w for w in warnings] == (free > 0.0).values.tolist() == [0, 1, 1]
    # the 5 mm heave stays near the static tension (about 92 N) throughout
    assert float(ds["tension_min"][0]) > 0.9 * float(ds["tension_static"][0])
    # unsettled where, and only where, the run stopped at max_periods without settling
    unsettled = (ds["steady_converged"] == 0).values
    assert ["unsettled: no steady state after 12 periods" in w for w in warnings] == (
        unsettled.tolist()
    )
    assert unsettled.tolist() == [False, False, True]
    assert float(ds["periods"][2]) == 12
    assert int(ds.attrs["cases_warned"]) == 2
    assert "0 failed, 2 with warnings" in printed
    assert re.search(r"\n +2 x slack, e\.g\.:\n +amplitude=0\.5: slack: ", printed), printed
    assert re.search(r"\n +1 x unsettled, e\.g\.:\n +amplitude=1: unsettled: ", printed)


#: a 150 m line in 100 m of water from a point 20 m above the seabed: at short distances
#: it hangs onto the seabed (the batch kernel's solution goes below it: the general solver
#: takes the case), at long ones it hangs free
HANGING = """\
name: hanging
environment: {fluid: water, depth: 100.0}
line:
  segments:
    - {length: 150.0, diameter: 0.05, mass_per_length: 10.0, axial_stiffness: 1.0e8}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -80.0]}
  b: {kind: fixed, position: [100.0, 0.0, -5.0]}
analysis:
  static: {method: catenary, nodes: 41}
sweep:
  ends.b.position.0: {values: [40.0, 80.0, 120.0, 140.0], name: distance}
"""


@pytest.mark.parametrize("extra", ["", "  line.segments.0.drag_normal: [1.2]\n"])
def test_a_fallback_from_the_batch_kernel_is_warned_where_the_line_touches_the_seabed(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], extra: str
) -> None:
    """On the array path (cablestudy.analyses.static_grid) and, with a swept path it does not take
    (drag
    in still water: no effect), case by case: the same cases, those on the seabed."""
    cfg = tmp_path / "hanging.yaml"
    cfg.write_text(HANGING + extra)
    ds, printed = _run(cfg, tmp_path, capsys)
    assert ds["status"].values.ravel().tolist() == [0, 0, 0, 0]
    touches = (ds["laid_length"] > 0.0).values.ravel()
    assert touches.tolist()[0] and not touches.tolist()[-1]  # both kinds in the sweep
    fallback = [
        str(w) == "fallback: solved one by one by the general solver, not the batched kernel "
        "(its solution touches the seabed)"
        for w in ds["warning"].values.ravel()
    ]
    assert fallback == touches.tolist()
    # each example after its case, by its sweep coordinates, on either path
    first = "distance=40, drag_normal=1.2" if extra else "distance=40"
    assert f"e.g.:\n           {first}: fallback: " in printed, printed
    assert re.search(rf"\n +{touches.sum()} x fallback, e\.g\.:\n", printed), printed


def test_the_laws_max_strain_still_fails_the_case(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """A law checked to increase up to a strain of 0.1 fails the 14.4 % case (status
    nonzero, the message naming max_strain), which then carries no warning: a warning is
    about results kept with status 0."""
    text = WIRE.replace("METHOD", "shooting").replace("STRAIN", "")
    text = text.replace(
        "axial_stiffness: 3.3e8}",
        "axial: {law: polynomial, coefficients: [3.3e8, 1.0e6], max_strain: 0.1}}",
    )
    cfg = tmp_path / "wire.yaml"
    cfg.write_text(text)
    ds, printed = _run(cfg, tmp_path, capsys)
    assert ds["status"].values[0] == 0 and ds["status"].values[1] != 0
    assert "(line.segments.0.axial.max_strain)" in str(ds["message"].values[1])
    assert ds["warning"].values.tolist() == ["", ""]
    assert int(ds.attrs["cases_warned"]) == 0 and "warnings by kind" not in printed


#: the aqwa seed's linear spring (configs/cable-spring-linear.yaml): 50 m, 2e5 N/m, towed
#: at B by a known force
SPRING = """\
name: spring
line:
  kind: spring
  length: 50.0
  axial: {law: linear, stiffness: 2.0e5}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: force, force: [3.0e4, 0.0, -4.0e4]}
analysis:
  static: {strain_warning: 0.006}
sweep:
  ends.b.force.0: {values: [1.0e4, 6.0e4], name: pull}
"""


def test_a_springs_strain_is_its_extension_over_its_length(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Towed by F, the spring stretches by |F| / k: a strain |F| / (k L) of 0.0041 at
    F = (1e4, 0, -4e4) N and 0.0072 at (6e4, 0, -4e4) N, against a limit of 0.006."""
    cfg = tmp_path / "spring.yaml"
    cfg.write_text(SPRING)
    ds, _ = _run(cfg, tmp_path, capsys)
    assert ds["status"].values.tolist() == [0, 0]
    low, high = (str(w) for w in ds["warning"].values)
    assert low == ""
    match = re.match(r"strain: largest strain (\S+) above the plausibility limit 0.006 ", high)
    assert match, high
    # printed to 4 significant digits (5e-4 relative)
    assert float(match.group(1)) == pytest.approx(math.hypot(6e4, 4e4) / (2e5 * 50.0), rel=1e-3)
