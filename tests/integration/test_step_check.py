"""The time domain's step check (issue 24, cablestudy/dynamics/step_check.py), through
``cablestudy run`` and the netCDF file: a line whose nodes land on and lift off the
seabed is run again over its last period at half the step, and a difference of its
end-tension extremes over ``step_tolerance`` of the period's range is a ``step``
warning naming both values; a line without such events is not checked."""

from __future__ import annotations

import re
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import yaml

import cablestudy.dynamics.system_timedomain as system_td
import cablestudy.dynamics.timedomain as line_td
from tests.system_contract import run_study, spread
from tests.validation.dynamics_helpers import run_direct

#: 320 m of chain (EA 5e8 N, no axial damping) from an anchor on the seabed in 100 m of
#: water to a fairlead 10 m below the surface, surged 2 m at 0.1 Hz: 16 elements, about
#: 120-142 m laid, 3-6 nodes landing and lifting off each period (issue 24's case)
LEG = """\
name: %s
environment: {fluid: water, depth: 100.0}
line:
  segments:
    - {length: 320.0, diameter: 0.1, mass_per_length: 50.0, axial_stiffness: 5.0e+8,
       drag_normal: 1.2}
ends:
  a: {kind: fixed, position: [300.0, 0.0, -100.0]}
  b: {kind: fixed, position: [10.0, 0.0, -10.0]}
analysis:
  static: {nodes: 11}
  dynamic:
    excitation: {end: b, direction: [1.0, 0.0, 0.0], amplitude: 2.0, frequency: 0.1}
    method: time
    elements: 16
"""

_VALUES = re.compile(
    r"step: the (maximum|minimum) tension at end ([AB]) over the last period depends on "
    r"the time step: (\S+) N at points_per_period (\d+), (\S+) N with the period run again "
    r"at (\d+) .* about points_per_period (\d+) is needed"
)


def _leg(name: str, sweep: str = "", **dynamic: object) -> str:
    text = LEG % name
    for key, value in dynamic.items():
        text += f"    {key}: {value}\n"
    return text + (f"sweep:\n{sweep}" if sweep else "")


def test_a_chain_landing_on_the_seabed_warns_of_its_step(tmp_path: Path) -> None:
    """At 64 steps a period (the default) the landings' axial ringing is damped by the
    step: the case keeps its values (status 0) and is warned, naming both extremes. The
    halved step's value lies nearer the 1024-step answer than the run's own: the check's
    second value is a step towards the converged one (MoorDyn at dtM 1.25e-4 s: minimum
    57.9 kN at the fairlead, ours at 1024: 61.2 kN, at 64: 71.1 kN)."""
    ds = run_study(tmp_path, _leg("steps", "  analysis.dynamic.points_per_period: [64, 1024]\n"))
    assert np.all(ds["status"] == 0)
    coarse = ds.sel(points_per_period=64)
    text = str(coarse["warning"].values)
    found = _VALUES.search(text)
    assert found, text
    what, end, a, p, b, p2, need = found.groups()
    assert (int(p), int(p2)) == (64, 128)
    assert int(need) > 128  # more than the halved step, which did not agree
    a, b = float(a), float(b)
    fine = ds.sel(points_per_period=1024)
    if end == "B":
        ref = float(fine[f"tension_{what[:3]}"])
        own = float(coarse[f"tension_{what[:3]}"])
    else:
        ref = float(fine[f"tension_envelope_{what[:3]}"].isel(s=0))
        own = float(coarse[f"tension_envelope_{what[:3]}"].isel(s=0))
    # the warning's first value is the run's own over its last period: the window's
    # extreme (two periods, settled to steady_tolerance 0.002 of the range) is within
    # that of it
    rng = float(coarse["tension_max"] - coarse["tension_min"])
    assert abs(a - own) <= 0.002 * rng
    assert abs(b - ref) < abs(a - ref)
    # the difference is over the tolerance the warning names (1 % of the range)
    assert abs(b - a) > 0.01 * rng


def test_the_check_leaves_the_values_alone_and_uses_its_tolerance(tmp_path: Path) -> None:
    """With ``step_tolerance: 1`` (a difference of the whole range allowed) the same run
    has no warning and the very same values: the check only reads."""
    warned = run_study(tmp_path, _leg("warned"))
    loose = run_study(tmp_path, _leg("loose", step_tolerance=1.0))
    assert str(warned["warning"].values).startswith("step:")
    assert str(loose["warning"].values) == ""
    for name in ("tension_max", "tension_min", "tension_mean", "tension_envelope_min"):
        np.testing.assert_array_equal(loose[name].values, warned[name].values)


def test_a_line_without_landings_is_not_checked(tmp_path: Path, monkeypatch) -> None:  # noqa: ANN001
    """The same chain in 400 m of water hangs clear of the seabed and stays taut: no
    event, no re-run (``step_check`` None), no warning."""
    seen = []
    real = line_td.simulate

    def spy(problem, **kw):  # noqa: ANN001, ANN202
        res = real(problem, **kw)
        seen.append(res)
        return res

    monkeypatch.setattr(line_td, "simulate", spy)
    study = yaml.safe_load(_leg("clear"))
    study["environment"]["depth"] = 400.0
    ds = run_study(tmp_path, yaml.safe_dump(study))
    assert int(ds["status"]) == 0 and str(ds["warning"].values) == ""
    assert seen and all(r.step_check is None for r in seen)


def test_the_re_run_restarts_from_the_saved_state_exactly() -> None:
    """Run again at the same step (factor 1) from the saved start of the last period,
    the extremes are the run's bit for bit: the saved state is the whole state."""
    study = yaml.safe_load(_leg("same"))
    res, _, _ = run_direct(study, keep_steps=False, step_check_factor=1.0)
    v = res.step_check
    assert v is not None and v.contact_changes > 0
    np.testing.assert_array_equal(v.fine, v.coarse)


@pytest.fixture
def system_runs(monkeypatch):  # noqa: ANN001, ANN201
    """The system time domain's results, with the re-run's factor to set."""
    seen = []
    real = system_td.simulate_system
    factor = {"value": 0.5}

    def spy(problem, **kw):  # noqa: ANN001, ANN202
        res = real(replace(problem, step_check_factor=factor["value"]), **kw)
        seen.append(res)
        return res

    monkeypatch.setattr(system_td, "simulate_system", spy)
    return seen, factor


BLOCK = (
    "  dynamic:\n    excitation: {body: hull, dof: surge, amplitude: 2.0, frequency: 0.1}\n"
    "    method: time\n    elements: 16\n"
)


def test_a_spread_whose_legs_land_warns_naming_the_line(tmp_path: Path, system_runs) -> None:  # noqa: ANN001
    """The 3-leg spread of that chain surged 2 m at 0.1 Hz (64 steps a period): status 0,
    a step warning naming the line and end, both values, the tolerance."""
    seen, _ = system_runs
    ds = run_study(tmp_path, spread("spreadstep", analysis=BLOCK))
    assert int(ds["status"]) == 0
    text = str(ds["warning"].values)
    assert re.search(r"step: the (maximum|minimum) tension at end [AB] of line l[123] ", text)
    assert "points_per_period 64" in text and "run again at 128" in text
    assert "analysis.dynamic.step_tolerance 0.01" in text
    v = seen[-1].step_check
    assert v is not None and not v.agrees and v.contact_changes > 0


def test_a_systems_re_run_restarts_exactly(tmp_path: Path, system_runs) -> None:  # noqa: ANN001
    seen, factor = system_runs
    factor["value"] = 1.0
    ds = run_study(tmp_path, spread("spreadsame", analysis=BLOCK))
    assert str(ds["warning"].values) == ""
    v = seen[-1].step_check
    assert v is not None and v.contact_changes > 0
    np.testing.assert_array_equal(v.fine, v.coarse)


@pytest.mark.parametrize(
    ("config", "words"),
    [
        ("catenary-pulley-dynamics", "a catenary line over sliding pulleys"),
        ("cable-spring-polynomial", "not used by a kind: spring line"),
        ("moustafa-figs2-5", "used by the time domain only"),
    ],
)
def test_step_tolerance_is_refused_where_nothing_would_use_it(
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
    config: str,
    words: str,
) -> None:
    """Given where no step check runs (a line over sliding pulleys: its own time
    domain; a spring line: no time step; method frequency: no time domain), the key is
    refused before any work, naming it (and its value, but for method frequency, whose
    message is the one of every time-domain key)."""
    from cablestudy.cli import main

    root = Path(__file__).resolve().parents[2]
    study = yaml.safe_load((root / "configs" / f"{config}.yaml").read_text())
    dyn = study["analysis"]["dynamic"]
    dyn["step_tolerance"] = 0.05
    if config == "moustafa-figs2-5":
        dyn["method"] = "frequency"
    cfg = tmp_path / f"{config}.yaml"
    cfg.write_text(yaml.safe_dump(study, sort_keys=False))
    assert main(["validate", str(cfg)]) == 2
    err = capsys.readouterr().err
    assert "step_tolerance" in err and words in err, err
    assert "0.05" in err or config == "moustafa-figs2-5", err
