"""Mooring systems in the time domain (issue 24), from the study file to the dataset:
every line driven by its body's motion, the free points integrated with the lines.

Physics checks: a system of one line is the one-line study bit for bit; two lines
joined at a massless, dragless point are one two-segment line; a slowly moved body
follows the static offset curve of the system statics; the body points follow the exact
rigid-body motion (tests/unit/test_system_kinematics.py)."""

from __future__ import annotations

import math

import numpy as np
import pytest
import xarray as xr

from cablestudy.analyses.counters import COUNTERS
from cablestudy.analyses.evaluate import evaluate_case
from cablestudy.analyses.system import evaluate_system_case, system_model
from cablestudy.analyses.variables import SYSTEM_OUTPUTS
from cablestudy.cli import main
from cablestudy.statics import STATIC_SOLVERS
from cablestudy.statics.system import solve_system
from cablestudy.study import parse_study_text
from cablestudy.study.grid import expand_cases
from cablestudy.study.loader import StudyError

SEG = "{length: %s, diameter: 0.1, mass_per_length: 20.0, axial_stiffness: 5.0e8%s}"

DYN = """\
  dynamic:
    excitation: %s
    method: time
    elements: %d
    points_per_period: 32
"""

#: a line from an anchor to a fairlead 10 m below the surface
ONE_LINE = (
    f"""\
name: one
environment: {{fluid: water}}
line:
  segments: [{SEG % (290.0, "")}]
ends:
  a: {{kind: fixed, position: [-250.0, 10.0, -100.0]}}
  b: {{kind: fixed, position: [0.0, 0.0, -10.0]}}
analysis:
  static: {{nodes: 11, tolerance: 1.0e-11}}
"""
    + DYN % ("{end: b, direction: [1.0, 0.0, 0.0], amplitude: 3.0, frequency: 0.1}", 20)
)

AS_SYSTEM = (
    f"""\
name: sys
environment: {{fluid: water}}
points:
  p: {{kind: fixed, position: [-250.0, 10.0, -100.0]}}
  q: {{kind: body, body: ship, offset: [0.0, 0.0, -10.0]}}
bodies:
  ship: {{kind: prescribed}}
lines:
  only: {{a: p, b: q, segments: [{SEG % (290.0, "")}]}}
analysis:
  static: {{nodes: 11, tolerance: 1.0e-11}}
"""
    + DYN % ("{body: ship, dof: surge, amplitude: 3.0, frequency: 0.1}", 20)
)


def _case(text: str, name: str = "sys.yaml"):  # noqa: ANN202
    (_, [case]) = expand_cases(parse_study_text(text, name))
    return case


@pytest.mark.parametrize(("seabed", "point"), [(False, False), (True, False), (False, True)])
def test_a_system_of_one_line_is_the_one_line_study_bit_for_bit(seabed: bool, point: bool) -> None:
    """Same line, same end motion (the body surges, so its fairlead moves exactly as the
    one-line study's end b; or, with no body, the fixed point moves on its own): the
    same discrete statics, the same steps, the same numbers, to the last bit; in deep
    water, and on a seabed (a third of the line laid: contact and friction as active
    sets, as the one-line step holds them)."""
    one_text, sys_text = ONE_LINE, AS_SYSTEM
    if point:
        sys_text = (
            sys_text.replace(
                "q: {kind: body, body: ship, offset: [0.0, 0.0, -10.0]}",
                "q: {kind: fixed, position: [0.0, 0.0, -10.0]}",
            )
            .replace("bodies:\n  ship: {kind: prescribed}\n", "")
            .replace(
                "{body: ship, dof: surge, amplitude: 3.0, frequency: 0.1}",
                "{point: q, direction: [1.0, 0.0, 0.0], amplitude: 3.0, frequency: 0.1}",
            )
        )
        assert "bodies" not in sys_text and "point: q" in sys_text
    if seabed:
        water = "{fluid: water, depth: 100.0, seabed: {friction: 0.5}}"
        one_text = one_text.replace("{fluid: water}", water)
        sys_text = sys_text.replace("{fluid: water}", water)
    one = evaluate_case(_case(one_text, "one.yaml"))
    sys = evaluate_system_case(_case(sys_text))
    assert one.status == 0 and sys.status == 0, (one.message, sys.message)
    assert (sys.data["laid_length"][0] > 50.0) == seabed
    for k in ("dynamic_steps", "newton_iterations", "periods"):
        assert sys.data[k] == one.data[k], k
    for mine, theirs in (
        ("tension_max_b", "tension_max"),
        ("tension_min_b", "tension_min"),
        ("tension_mean_b", "tension_mean"),
    ):
        assert sys.data[mine][0] == one.data[theirs], mine
    np.testing.assert_array_equal(
        sys.data["tension_envelope_max"][0], one.data["tension_envelope_max"]
    )
    np.testing.assert_array_equal(
        sys.data["tension_envelope_min"][0], one.data["tension_envelope_min"]
    )


#: no drag, no added mass: then a junction node of two lines and the node between two
#: segments of one line carry the same forces (drag and added mass would take the
#: node's tangent, which differs: the chord of its two elements against each line's own)
BARE = ", drag_normal: 0.0, drag_tangential: 0.0, added_mass_normal: 0.0"
SERIES = f"""\
name: series
environment: {{fluid: water}}
points:
  anchor: {{kind: fixed, position: [-270.0, 0.0, -100.0]}}
  m1: {{kind: free, position: [-160.0, 0.0, -85.0]}}
  m2: {{kind: free, position: [-80.0, 0.0, -60.0]}}
  fair: {{kind: body, body: ship, offset: [0.0, 0.0, -10.0]}}
bodies:
  ship: {{kind: prescribed}}
lines:
  lower: {{a: anchor, b: m1, segments: [{SEG % (100.0, BARE)}]}}
  middle: {{a: m1, b: m2, segments: [{SEG % (100.0, BARE)}]}}
  upper: {{a: m2, b: fair, segments: [{SEG % (100.0, BARE)}]}}
analysis:
  static: {{nodes: 11, tolerance: 1.0e-11}}
"""
WHOLE = f"""\
name: whole
environment: {{fluid: water}}
points:
  anchor: {{kind: fixed, position: [-270.0, 0.0, -100.0]}}
  fair: {{kind: body, body: ship, offset: [0.0, 0.0, -10.0]}}
bodies:
  ship: {{kind: prescribed}}
lines:
  all: {{a: anchor, b: fair, segments: [{", ".join([SEG % (100.0, BARE)] * 3)}]}}
analysis:
  static: {{nodes: 11, tolerance: 1.0e-11}}
"""
RUN = "    duration: 30.0\n    ramp_periods: 1.0\n"
SURGE = "{body: ship, dof: surge, amplitude: 3.0, frequency: 0.1}"


def test_lines_at_bare_junctions_are_one_line_of_segments() -> None:
    """Three lines in series joined at two massless, dragless free points (the middle
    line has both ends on them) against one line of the three segments, 10 elements
    each in both: the junctions' unknowns solved by the bordered (Schur) solve give the
    motion of the same nodes inside one banded line, so the end tensions agree to what
    the Newton iterations leave. Each step converges to a residual force of
    newton_tolerance (1e-7) times the largest static tension; that force error moves the
    tensions by about as much relative to them, fed on over the run's few hundred steps:
    1e-5 relative bounds it with a factor of a thousand in hand (measured: 3e-9)."""
    three = evaluate_system_case(_case(SERIES + DYN % (SURGE, 10) + RUN))
    one = evaluate_system_case(_case(WHOLE + DYN % (SURGE, 30) + RUN))
    assert three.status == 0 and one.status == 0, (three.message, one.message)
    assert three.data["dynamic_steps"] == one.data["dynamic_steps"]
    for k in ("tension_max", "tension_min"):
        np.testing.assert_allclose(three.data[f"{k}_a"][0], one.data[f"{k}_a"][0], rtol=1e-5)
        np.testing.assert_allclose(three.data[f"{k}_b"][2], one.data[f"{k}_b"][0], rtol=1e-5)
    for k in ("body_force_max", "body_force_min"):
        np.testing.assert_allclose(three.data[k], one.data[k], rtol=1e-5, atol=1e-3)


#: a clump between two anchored legs and a bridle to the body, a third leg to the body
CLUMP = f"""\
name: clump
environment: {{fluid: water}}
points:
  anchor1: {{kind: fixed, position: [-300.0, -40.0, -100.0]}}
  anchor2: {{kind: fixed, position: [-300.0, 40.0, -100.0]}}
  anchor3: {{kind: fixed, position: [250.0, 0.0, -100.0]}}
  clump:
    {{kind: free, position: [-60.0, 0.0, -60.0], mass: 3000.0, volume: 0.2, added_mass: 400.0,
     drag_area: 0.5}}
  fair1: {{kind: body, body: buoy, offset: [-5.0, 0.0, -10.0]}}
  fair2: {{kind: body, body: buoy, offset: [5.0, 0.0, -10.0]}}
bodies:
  buoy: {{kind: prescribed, position: [0.0, 0.0, 0.0, 0.0, 0.0, 0.0]}}
lines:
  leg1: {{a: anchor1, b: clump, segments: [{SEG % (260.0, "")}]}}
  leg2: {{a: anchor2, b: clump, segments: [{SEG % (260.0, "")}]}}
  bridle: {{a: clump, b: fair1, segments: [{SEG % (70.0, "")}]}}
  leg3: {{a: anchor3, b: fair2, segments: [{SEG % (275.0, "")}]}}
analysis:
  static: {{nodes: 11, tolerance: 1.0e-11}}
"""


def _slow(elements: int) -> dict:
    text = CLUMP + DYN % ("{body: buoy, dof: surge, amplitude: 4.0, period: 400.0}", elements)
    rec = evaluate_system_case(
        _case(text + "    steady_window: 1\n    min_periods: 1\n    ramp_periods: 0.5\n")
    )
    assert rec.status == 0, rec.message
    return rec.data


def test_a_slowly_moved_body_follows_the_static_offset_curve() -> None:
    """Surge 4 m over 400 s (the lines' lowest periods are seconds): the extremes of the
    surge force of the lines on the body are the system statics' at -4 m and +4 m, but
    for what moves the lines there. Inertia: at most the whole moving mass (lines with
    their added mass, the clump with its own) times the body's peak acceleration
    A (2 pi / T)^2, about 27 N; drag at v = 2 pi A / T = 0.06 m/s is a few newtons.
    Discretisation: second order in the element length, estimated by refinement (the
    change from 20 to 40 elements per line, doubled to bound the 40-element error).
    Measured: 19 N and 27 N off, against a tolerance of 27 N + 26 N."""
    case = _case(CLUMP + DYN % ("{body: buoy, dof: surge, amplitude: 4.0, period: 400.0}", 20))
    system = system_model(case.study)
    static = {}
    for x in (-4.0, 4.0):
        moved = system.__class__(
            **{**system.__dict__, "body_position": np.array([[x, 0.0, 0.0, 0.0, 0.0, 0.0]])}
        )
        static[x] = solve_system(moved, STATIC_SOLVERS["catenary"]).body_force[0, 0]
    coarse, fine = _slow(20), _slow(40)
    st = case.study
    rho = st.environment.density
    moving = sum(
        (seg.mass_per_length + rho * seg.added_mass_normal * seg.area) * seg.length
        for line in st.lines.values()
        for seg in line.segments
    )
    moving += st.points["clump"].mass + st.points["clump"].added_mass
    inertia = moving * 4.0 * (2.0 * math.pi / 400.0) ** 2
    for key, x in (("body_force_max", -4.0), ("body_force_min", 4.0)):
        refinement = 2.0 * abs(coarse[key][0, 0] - fine[key][0, 0])
        assert abs(fine[key][0, 0] - static[x]) <= inertia + refinement, (key, fine[key], static[x])
    assert static[-4.0] - static[4.0] > 100.0 * (inertia + refinement)  # a real offset curve


@pytest.fixture(scope="module")
def case8(tmp_path_factory: pytest.TempPathFactory) -> xr.Dataset:
    """MoorPy's case8 (nine polyester lines, three junctions, a spar) surged 2 m at
    0.1 Hz, run by the command line from its config file (10 elements per line)."""
    from pathlib import Path

    tmp = tmp_path_factory.mktemp("case8")
    text = (Path(__file__).parents[2] / "configs" / "system-case8-surge.yaml").read_text()
    cfg = tmp / "case8.yaml"
    cfg.write_text(text.replace("elements: 20", "elements: 10"))
    args = ["run", str(cfg), "--out", str(tmp), "--no-cache", "--no-progress"]
    assert main([*args, "--scheduler", "synchronous"]) == 0
    return xr.load_dataset(tmp / "system-case8-surge.nc")


def test_case8_runs_end_to_end_with_the_contract_names(case8: xr.Dataset) -> None:
    ds = case8
    assert int(ds.status) == 0 and int(ds.dynamic_status) == 0, str(ds.message.values)
    n_lines = ds.sizes["line"]
    assert n_lines == 9
    for end in ("a", "b"):
        for q in ("max", "min", "mean"):
            var = ds[f"tension_{q}_{end}"]
            assert var.dims == ("line",) and var.attrs["units"] == "N"
            assert np.all(np.isfinite(var))
    for k in ("tension_envelope_max", "tension_envelope_min"):
        assert ds[k].dims == ("line", "s")
    for k in ("body_force_max", "body_force_min"):
        assert ds[k].dims == ("body", "dof")
        assert list(ds.dof.values) == ["surge", "sway", "heave", "roll", "pitch", "yaw"]
    assert str(ds.dynamic_method.values) == "time"
    # auto: at 2 m the bridles' shape changes by more than their sag allows
    reason = str(ds.dynamic_method_reason.values)
    assert reason.startswith("auto: line '") and "large motion" in reason, reason
    for k in ("tension_a", "body_stiffness", "point_position"):  # the statics stay
        assert k in ds
    # the static tension lies within each end's range, but for the 10-element model's
    # own rest tension, up to 7.5e-4 off the continuous statics' (measured on the leg
    # across the motion, whose tension barely moves: 1e-3 bounds it); the ends of the
    # envelope are the end extremes; the spar's surge force swings about its static value
    for end in ("a", "b"):
        stat = ds[f"tension_{end}"].values
        assert np.all(ds[f"tension_min_{end}"].values <= stat * (1.0 + 1e-3))
        assert np.all(stat <= ds[f"tension_max_{end}"].values * (1.0 + 1e-3))
    np.testing.assert_allclose(ds.tension_envelope_max[:, 0], ds.tension_max_a, rtol=1e-12)
    np.testing.assert_allclose(ds.tension_envelope_max[:, -1], ds.tension_max_b, rtol=1e-12)
    surge = ds.body_force.sel(dof="surge").values[0]
    assert ds.body_force_min.sel(dof="surge").values[0] < surge
    assert surge < ds.body_force_max.sel(dof="surge").values[0]
    # MoorDyn case8's layout: legs 1, 3 mirror each other about the spar's x-z plane
    names = list(ds.line.values)
    np.testing.assert_allclose(
        ds.tension_max_b.sel(line=names[2]), ds.tension_max_b.sel(line=names[8]), rtol=1e-6
    )


def test_a_sweep_of_the_motion_shares_the_statics_and_the_model() -> None:
    """Amplitude and frequency swept over a system: one static solve and one model
    assembly (the lines discretised, packed, at their discrete equilibrium) serve all
    four cases; larger motion, larger range."""
    text = (
        CLUMP
        + DYN % ("{body: buoy, dof: surge, amplitude: 1.0, frequency: 0.1}", 10)
        + (
            "sweep:\n  analysis.dynamic.excitation.amplitude: [0.5, 1.0]\n"
            "  analysis.dynamic.excitation.frequency: [0.1, 0.125]\n"
        )
    )
    axes, cases = expand_cases(parse_study_text(text, "sys.yaml"))
    assert [a.name for a in axes] == ["amplitude", "frequency"]
    from cablestudy.analyses import system as system_cases
    from cablestudy.analyses import system_dynamic as system_dynamic_cases

    def cold() -> None:  # earlier tests solved the same statics
        system_cases._STATICS_CACHE.clear()
        system_dynamic_cases._STATIC_CACHE.clear()
        system_dynamic_cases._MODEL_CACHE.clear()

    cold()
    before = COUNTERS.copy()
    recs = [evaluate_system_case(c) for c in cases]
    assert all(r.status == 0 for r in recs), [r.message for r in recs]
    assert COUNTERS["system_static_solves"] - before["system_static_solves"] == 1
    assert COUNTERS["system_assemblies"] - before["system_assemblies"] == 1
    # what the sweep shares is what each case alone computes, bit for bit
    for case, shared in zip(cases, recs, strict=True):
        cold()
        alone = evaluate_system_case(case)
        assert (alone.status, alone.message, alone.warning) == (
            shared.status,
            shared.message,
            shared.warning,
        )
        assert alone.data.keys() == shared.data.keys()
        for name, value in alone.data.items():
            np.testing.assert_array_equal(value, shared.data[name], err_msg=name)
    ranges = [r.data["tension_max_b"] - r.data["tension_min_b"] for r in recs]
    assert np.all(ranges[2] > ranges[0]) and np.all(ranges[3] > ranges[1])


def test_pitch_yaw_and_tables_run_through_the_study() -> None:
    """A body pitched harmonically and yawed by a periodic table, a point moved on its
    own: the motions reach the lines (the yaw moment swings both ways about zero)."""
    exc = (
        "\n      - {body: buoy, dof: pitch, amplitude: 0.05, frequency: 0.1}"
        "\n      - {body: buoy, dof: yaw, table: [[0, 0.0], [2.5, 0.1], [5, 0.0], "
        "[7.5, -0.1], [10, 0.0]], periodic: true}"
        "\n      - {point: anchor3, direction: [0, 0, 1], amplitude: 0.2, period: 10.0}"
    )
    rec = evaluate_system_case(_case(CLUMP + DYN % (exc, 10)))
    assert rec.status == 0, rec.message
    yaw = SYSTEM_OUTPUTS["body_force_max"].dims.index("dof")
    assert yaw == 1
    assert rec.data["body_force_max"][0, 5] > 0.0 > rec.data["body_force_min"][0, 5]
    assert rec.data["body_force_max"][0, 4] > rec.data["body_force_min"][0, 4]


def _error(text: str) -> str:
    with pytest.raises(StudyError) as info:
        expand_cases(parse_study_text(text, "sys.yaml"))
    return str(info.value)


@pytest.mark.parametrize(
    ("excitation", "extra", "words"),
    [
        ("{body: boat, dof: surge, amplitude: 1.0, frequency: 0.1}", "", "no body of that name"),
        ("{body: buoy, dof: swing, amplitude: 1.0, frequency: 0.1}", "", "'surge'"),
        ("{point: fairX, direction: [1, 0, 0], amplitude: 1.0, frequency: 0.1}", "", "fairX"),
        ("{point: clump, direction: [1, 0, 0], amplitude: 1.0, frequency: 0.1}", "", "free point"),
        ("{end: b, direction: [1, 0, 0], amplitude: 1.0, frequency: 0.1}", "", "dof"),
        (
            "[{body: buoy, dof: yaw, table: [[0, 0], [1, 1], [2, 0], [3, 0]]}, "
            "{body: buoy, dof: yaw, table: [[0, 0], [1, 2], [2, 0], [3, 0]]}]",
            "    duration: 10.0\n",
            "already moved by a table",
        ),
        (
            "{body: buoy, dof: surge, amplitude: 1.0, frequency: 0.1}",
            "    method: frequency\n",
            "method 'time'",
        ),
        (
            "{body: buoy, dof: surge, spectrum: [[0.05, 1.0], [0.2, 1.0]], end: a}",
            "",
            "end",
        ),
        (
            "{body: buoy, dof: surge, amplitude: 1.0, frequency: 0.1}",
            "    history: {points: [10.0]}\n",
            "history_tension_a",
        ),
    ],
)
def test_system_dynamics_faults_name_the_field(excitation: str, extra: str, words: str) -> None:
    text = CLUMP + (DYN % (excitation, 10)).replace("    method: time\n", "") + extra
    if "method: frequency" in extra:
        text = text.replace("    elements:", "    elements:", 1)
    message = _error(text)
    assert words in message, message


def test_a_one_line_study_refuses_a_body_motion() -> None:
    text = ONE_LINE.replace(
        "{end: b, direction: [1.0, 0.0, 0.0], amplitude: 3.0, frequency: 0.1}",
        "{body: ship, dof: surge, amplitude: 3.0, frequency: 0.1}",
    )
    assert "a one-line study moves its ends" in _error(text)


def test_history_has_a_line_dimension() -> None:
    text = CLUMP + DYN % ("{body: buoy, dof: surge, amplitude: 1.0, frequency: 0.1}", 10)
    rec = evaluate_system_case(
        _case(text + "    history: {periods: 1.0, samples_per_period: 16}\n")
    )
    assert rec.status == 0, rec.message
    assert SYSTEM_OUTPUTS["history_tension_b"].dims == ("line", "time")
    h = rec.data["history_tension_b"]
    assert h.shape == (4, 17) and rec.data["history_time"].shape == (17,)
    # the record lies within the steady window's extremes (it is one of its periods)
    assert np.all(h <= rec.data["tension_max_b"][:, None] * (1 + 1e-9))
    assert np.all(h >= rec.data["tension_min_b"][:, None] * (1 - 1e-9))


def test_an_unsettled_run_says_so() -> None:
    """Three periods, two of them the ramp: the end tensions cannot be shown settled,
    and the case says so (its extremes kept, as a one-line study's)."""
    text = CLUMP + DYN % ("{body: buoy, dof: surge, amplitude: 1.0, frequency: 0.1}", 10)
    rec = evaluate_system_case(_case(text + "    max_periods: 3\n"))
    assert rec.status == 0 and int(rec.data["steady_converged"]) == 0
    assert rec.warning.startswith("unsettled")


def test_a_body_moved_by_a_spectrum() -> None:
    """JONSWAP waves times a heave RAO of one (the body follows the sea surface): the
    motion runs as the spectrum's lines with seeded phases, as a line end's; the run is
    periodic in the lowest line's period (here 16 lines up to 0.25 Hz: 64 s). Heaving
    harder (Hs doubled) widens every line's tension range."""
    exc = (
        "{body: buoy, dof: heave, wave_spectrum: {hs: %s, tp: 10.0}, "
        "rao: [[0.0, 1.0], [0.25, 1.0]], components: 16, seed: 3}"
    )
    recs = [
        evaluate_system_case(
            _case(CLUMP + DYN % (exc % hs, 10) + "    ramp_periods: 0.25\n    max_periods: 3\n")
        )
        for hs in ("1.0", "2.0")
    ]
    assert all(r.status == 0 for r in recs), [r.message for r in recs]
    ranges = [r.data["tension_max_b"] - r.data["tension_min_b"] for r in recs]
    assert np.all(ranges[1] > ranges[0])
    assert recs[0].data["periods"] == 3.0


def test_a_free_leg_on_a_rough_seabed_is_its_one_line_study() -> None:
    """The clump system on a seabed with friction 0.8 (legs laid from their anchors,
    friction holding their laid parts): its third leg, from an anchor straight to the
    body, touches no free point, so it moves as the one-line study of that leg under
    the same fairlead motion. Not bit for bit: the system's Newton iterations run until
    every line has converged, which leaves this leg's residual below, not at, the
    one-line run's; the extremes agree to what that residual (1e-7 of the largest
    static tension, over a few hundred steps) moves them: 1e-5 relative (measured 5e-8)."""
    rough = "{fluid: water, depth: 100.0, seabed: {friction: 0.8}}"
    surge = "{body: buoy, dof: surge, amplitude: 2.0, frequency: 0.1}"
    # leg3 slacker than CLUMP's (290 m for a 261 m chord): a settled response (at 275 m
    # it snaps taut every period and never settles, in both models)
    text = CLUMP.replace("{fluid: water}", rough).replace(SEG % (275.0, ""), SEG % (290.0, ""))
    text += DYN % (surge, 20)
    rec = evaluate_system_case(_case(text))
    assert rec.status == 0, rec.message
    assert int(rec.data["steady_converged"]) == 1
    assert rec.data["laid_length"][0] > 10.0  # leg1 lies on the seabed
    leg3 = (
        f"""\
name: leg3
environment: {rough}
line:
  segments: [{SEG % (290.0, "")}]
ends:
  a: {{kind: fixed, position: [250.0, 0.0, -100.0]}}
  b: {{kind: fixed, position: [5.0, 0.0, -10.0]}}
analysis:
  static: {{nodes: 11, tolerance: 1.0e-11}}
"""
        + DYN % ("{end: b, direction: [1.0, 0.0, 0.0], amplitude: 2.0, frequency: 0.1}", 20)
    )
    one = evaluate_case(_case(leg3, "leg3.yaml"))
    assert one.status == 0, one.message
    assert one.data["laid_length"] > 10.0
    np.testing.assert_allclose(rec.data["tension_max_b"][3], one.data["tension_max"], rtol=1e-5)
    np.testing.assert_allclose(rec.data["tension_min_b"][3], one.data["tension_min"], rtol=1e-5)
    np.testing.assert_allclose(
        rec.data["tension_envelope_max"][3], one.data["tension_envelope_max"], rtol=1e-5
    )


def test_in_a_current_the_dynamics_do_not_depend_on_the_static_method() -> None:
    """The clump system in a sheared current: the time domain starts from the discrete
    model's own equilibrium, found from either static method's solution, so both give
    the same response; they differ by what the Newton tolerances leave (static 1e-9,
    dynamic 1e-7 of the largest tension): 1e-6 relative (measured 1.2e-9)."""
    water = "{fluid: water, current: [{z: 0.0, speed: 0.5}, {z: -100.0, speed: 0.2}]}"
    surge = "{body: buoy, dof: surge, amplitude: 1.0, frequency: 0.1}"
    out = {}
    for method in ("catenary", "discrete"):
        text = CLUMP.replace("{fluid: water}", water).replace(
            "static: {nodes: 11,", f"static: {{method: {method}, nodes: 11,"
        )
        rec = evaluate_system_case(_case(text + DYN % (surge, 10)))
        assert rec.status == 0, rec.message
        out[method] = rec.data
    for k in ("tension_max_a", "tension_min_a", "tension_max_b", "tension_min_b"):
        np.testing.assert_allclose(out["discrete"][k], out["catenary"][k], rtol=1e-6)
