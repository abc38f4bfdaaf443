"""Mooring systems in dynamics (issue 24) checked from outside: studies written from
DESIGN.md and docs/guide/systems.md (tests/system_dynamics_contract.py), run through
``cablestudy run CONFIG --out DIR`` and read back from the netCDF file, against the
contract (tests/system_contract.py: names, dimensions, units, status/message, no NaN at
status 0) and against the physics a user checks: a held system stays at its static
state (every static load is in the dynamic model, and the lines' forces on free points
are the statics'), a body pitched through a large angle moves its fairlead by the exact
rotation, a phase is a time shift, a slowly moved body follows the static offset curve,
the fairleads moved on their own are the body moved, the frequency and time domains
agree with free points (added mass, drag) and converge together as the elements are
refined, and a study whose every case fails keeps its outputs as NaN.

Not repeated here (tests/integration/test_contract_external_system.py): the dof sweep's
dimension, mirrored legs in surge and sway, the spread turned about z, a system of one
line against the one-line study, FD against TD on a 3-leg spread, the bridle's motion
kinds and sweeps through the contract, bad references refused by name.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import yaml

from cablestudy.cli import main
from tests.system_contract import contract_problems, run_study, spread, statics_problems
from tests.system_dynamics_contract import (
    bridle,
    one_leg,
    periodic_table,
    pitched_offset,
    run,
    run_failing,
    time_domain,
)

ENDS = [f"tension_{m}_{e}" for m in ("max", "min") for e in "ab"]


def test_a_held_system_stays_at_its_static_state(tmp_path: Path) -> None:
    """The bridle (a clump and a buoy at junctions) in a sheared, turning current, its
    buoy pushed by a constant force, the ship turned in all three angles and moved off
    its origin, a riser with bending stiffness, a bridle of a polynomial law, held still
    (amplitude 0) after statics by method discrete at the dynamic mesh (nodes =
    elements + 1: the same lumped-mass model): every line's end tensions and the body
    force stay at the static ones. The time domain starts at that equilibrium, so only
    the Newton tolerance (1e-7 of the static tension) moves them: 1e-5 of the largest
    tension bounds it. Each line's tension at a free point was the end element's pull
    (without the half element's weight the point carries in the statics): 2.3e-2 off
    at the clump and the buoy, 0 at the anchors and the ship
    (cablestudy/dynamics/system_march.py end_forces)."""
    study = bridle("held")
    study["environment"]["current"] = [
        {"z": 0.0, "speed": 0.8, "heading_deg": 30.0},
        {"z": -200.0, "speed": 0.3, "heading_deg": 60.0},
    ]
    study["points"]["buoy"]["force"] = [3000.0, 1000.0, -5000.0]
    study["bodies"]["ship"]["position"] = [5.0, -3.0, 1.0, 0.05, -0.04, 0.3]
    study["lines"]["riser"]["segments"][0]["bending_stiffness"] = 2.0e5
    br1 = study["lines"]["br1"]["segments"][0]
    br1["axial"] = {"law": "polynomial", "coefficients": [br1.pop("axial_stiffness"), 5.0e9]}
    study["analysis"] = {
        "static": {"nodes": 9, "method": "discrete"},
        "dynamic": time_domain(
            {"body": "ship", "dof": "surge", "amplitude": 0.0, "frequency": 0.1}, periods=6
        ),
    }
    ds = run(tmp_path, study)
    assert np.all(ds["status"] == 0), ds["message"].values
    assert contract_problems(ds, dynamic=True) == []
    big = float(ds["tension_b"].max())
    for e in "ab":
        for m in ("max", "min", "mean"):
            diff = np.abs(ds[f"tension_{m}_{e}"] - ds[f"tension_{e}"]).values
            assert diff.max() < 1e-5 * big, (m, e, diff / big)
    for m in ("max", "min"):
        diff = np.abs(ds[f"body_force_{m}"] - ds["body_force"]).values
        assert diff.max() < 1e-5 * big, (m, diff / big)


def test_a_study_whose_every_case_fails_keeps_its_outputs_as_nan(tmp_path: Path) -> None:
    """A 3-leg spread surged at two amplitudes under a 0.1 ms time limit: every case
    fails in the dynamics (status and message), and the dataset still has every
    dynamic output, NaN (DESIGN.md: a failed case is NaN in its data variables, never
    dropped). They were missing: the variables were the keys of the cases that
    succeeded."""
    text = spread(
        "failing",
        analysis=(
            "  time_limit: 1.0e-4\n  dynamic:\n"
            "    excitation: {body: hull, dof: surge, amplitude: 2.0, frequency: 0.1}\n"
            "    method: time\n    elements: 8\n    points_per_period: 32\n    max_periods: 12\n"
        ),
        sweep="  analysis.dynamic.excitation.amplitude: [1.0, 2.0]\n",
    )
    code, ds = run_failing(tmp_path, text)
    assert code == 3  # every case failed (docs/guide/cli.md)
    assert np.all(ds["status"] != 0)
    assert all("time limit" in str(m) for m in ds["message"].values)
    assert contract_problems(ds, dynamic=True) == []
    for name in (*ENDS, "tension_envelope_max", "body_force_max", "body_force_min"):
        assert bool(np.isnan(ds[name]).all()), name
    # the statics of each case are kept
    assert bool(np.isfinite(ds["tension_b"]).all())


def test_a_large_pitch_moves_the_fairlead_by_the_exact_rotation(tmp_path: Path) -> None:
    """A single leg on a body pitched 0.2 rad (11.5 deg) at 0.1 Hz by a periodic table,
    against the same body moved by surge and heave tables that carry its fairlead
    along R_y(pitch) p - p exactly (one fairlead: the line sees only that point). The
    tables (65 rows a period, cubic splines) differ by the spline's h^4 error of the
    two forms of the motion: measured 4e-5 of the tension range, bounded by 1e-3. The
    small-angle motion (p_z pitch, -p_x pitch) is 0.2 of the range away: the check sees
    a rotation taken small-angle."""
    period, angle = 10.0, 0.2
    pitch = angle * np.sin(2.0 * np.pi * np.linspace(0.0, 1.0, 65))
    move = pitched_offset(np.array([10.0, 0.0, -10.0]), pitch)
    small = np.stack([-10.0 * pitch, 0.0 * pitch, -10.0 * pitch], axis=-1)

    def tables(name: str, rows: list[tuple[str, np.ndarray]]) -> dict:
        study = one_leg(name)
        exc = [
            {"body": "hull", "dof": dof, "table": periodic_table(period, v), "periodic": True}
            for dof, v in rows
        ]
        study["analysis"]["dynamic"] = time_domain(exc)
        return run(tmp_path, study)

    rotated = tables("pitched", [("pitch", pitch)])
    moved = tables("moved", [("surge", move[:, 0]), ("heave", move[:, 2])])
    linear = tables("smallangle", [("surge", small[:, 0]), ("heave", small[:, 2])])
    for ds in (rotated, moved, linear):
        assert np.all(ds["status"] == 0), ds["message"].values
        assert contract_problems(ds, dynamic=True) == []
    rotated, moved, linear = (ds.sel(line="l1") for ds in (rotated, moved, linear))
    span = float(rotated["tension_max_b"] - rotated["tension_min_b"])
    for name in ENDS:
        assert abs(float(rotated[name] - moved[name])) < 1e-3 * span, name
    assert abs(float(rotated["tension_max_b"] - linear["tension_max_b"])) > 0.1 * span


def test_a_phase_of_the_heave_is_a_time_shift(tmp_path: Path) -> None:
    """The leg's body heaved 1 m at 0.1 Hz for a fixed 100 s, with phase 0 and 90 deg,
    histories kept (2 periods, 32 samples a period, on (line, time)): sin(w t + pi/2)
    = sin(w (t + T/4)), so the 90-degree record is the other shifted by 8 samples. The
    runs differ only by their start (the ramp), decayed over 8 periods below the
    steady tolerance (2e-3 of the range); measured 1e-11 of the range."""

    def heave(phase: float) -> object:
        study = one_leg(f"phase{int(phase)}")
        dyn = time_domain(
            {"body": "hull", "dof": "heave", "amplitude": 1.0, "frequency": 0.1,
             "phase_deg": phase},
            history={"periods": 2.0, "samples_per_period": 32},
        )  # fmt: skip
        dyn.pop("max_periods")
        dyn["duration"] = 100.0
        study["analysis"]["dynamic"] = dyn
        return run(tmp_path, study)

    first, later = heave(0.0), heave(90.0)
    for ds in (first, later):
        assert np.all(ds["status"] == 0) and contract_problems(ds, dynamic=True) == []
        assert ds["history_tension_b"].dims == ("line", "time")
        assert ds["history_tension_b"].attrs["units"] == "N"
        assert ds["history_time"].attrs["units"] == "s"
    np.testing.assert_array_equal(first["history_time"], later["history_time"])
    a = first["history_tension_b"].sel(line="l1").values
    b = later["history_tension_b"].sel(line="l1").values
    span = float(a.max() - a.min())
    assert np.abs(b[:-8] - a[8:]).max() < 2e-3 * span
    assert np.abs(b - a).max() > 0.5 * span  # unshifted, they differ


def test_a_slowly_moved_body_follows_the_static_offset_curve(tmp_path: Path) -> None:
    """The leg's body surged 3 m at 0.002 Hz against the statics (method discrete at
    the dynamic mesh) of the body offset -3, 0, +3 m: the maximum fairlead tension is
    the static one at -3 m, the minimum at +3 m, the anchor's alike, and the body's
    surge force the static one. The dynamic part (inertia, drag) falls as the frequency
    squared: 240 N at 0.01 Hz, 10 N at 0.002 Hz (measured), so 1e-3 of the 28 kN static
    range bounds it."""
    static = one_leg("offsets")
    static["analysis"]["static"]["method"] = "discrete"
    static["sweep"] = {"bodies.hull.position.0": {"values": [-3.0, 0.0, 3.0], "name": "surge"}}
    curve = run(tmp_path, static)
    assert statics_problems(curve) == []
    slow = one_leg("slow")
    slow["analysis"]["dynamic"] = time_domain(
        {"body": "hull", "dof": "surge", "amplitude": 3.0, "frequency": 0.002}
    )
    ds = run(tmp_path, slow)
    assert np.all(ds["status"] == 0) and contract_problems(ds, dynamic=True) == []
    ds = ds.sel(line="l1")
    span = float(curve["tension_b"].max() - curve["tension_b"].min())
    for e in "ab":
        t = curve[f"tension_{e}"].sel(line="l1")
        assert abs(float(ds[f"tension_max_{e}"]) - float(t.sel(surge=-3.0))) < 1e-3 * span
        assert abs(float(ds[f"tension_min_{e}"]) - float(t.sel(surge=3.0))) < 1e-3 * span
    f = curve["body_force"].sel(body="hull", dof="surge")
    got = ds["body_force_max"].sel(body="hull", dof="surge")
    assert abs(float(got) - float(f.sel(surge=-3.0))) < 1e-3 * span


def test_the_fairleads_moved_on_their_own_are_the_body_moved(tmp_path: Path) -> None:
    """A 3-leg spread surged 2 m at 0.1 Hz, against its three fairleads each moved 2 m
    along x on its own (point excitations beside their body): the same held-node
    motions, so the same tensions up to the Newton tolerance (1e-7 of the static
    tension; 1e-5 of the largest bounds the differences of the step control)."""
    surge = "{body: hull, dof: surge, amplitude: 2.0, frequency: 0.1}"
    points = (
        "[" + ", ".join(
            f"{{point: f{i}, direction: [1, 0, 0], amplitude: 2.0, frequency: 0.1}}"
            for i in (1, 2, 3)
        ) + "]"
    )  # fmt: skip
    block = (
        "  dynamic:\n    excitation: %s\n    method: time\n    elements: 8\n"
        "    points_per_period: 32\n    max_periods: 12\n"
    )
    body = run_study(tmp_path, spread("bodymoved", analysis=block % surge))
    own = run_study(tmp_path, spread("pointsmoved", analysis=block % points))
    for ds in (body, own):
        assert np.all(ds["status"] == 0) and contract_problems(ds, dynamic=True) == []
    big = float(body["tension_max_b"].max())
    for name in ENDS:
        np.testing.assert_allclose(own[name].values, body[name].values, rtol=0, atol=1e-5 * big)


def test_free_points_frequency_and_time_domain_agree_and_converge(tmp_path: Path) -> None:
    """The bridle in 400 m of water (every line clear of the seabed; the clump's and the
    buoy's mass, added mass and drag area in both models), its ship surged 0.05 m and
    pitched 0.004 rad a quarter period later, an anchor heaved 0.05 m on its own at
    -60 deg (phases across degrees of freedom and points), all at 0.1 Hz: each line's
    end extremes by the frequency domain (static plus and minus the amplitude)
    and by the time domain. Their difference is the time domain's discrete statics
    against the catenary (second order in the element length): measured 2.5e-3 of the
    static tension at 10 elements, 6.5e-4 at 20; so within 5e-3 at 10, 1.2e-3 at 20, and
    at least 3 times smaller at 20 than at 10 (4 for order 2); the ship's force
    extremes within 2e-3 of its largest static force."""
    worst = {}
    for elements in (10, 20):
        runs = {}
        for method in ("frequency", "time"):
            study = bridle(f"deep_{method}_{elements}", depth=400.0)
            exc = [
                {"body": "ship", "dof": "surge", "amplitude": 0.05, "frequency": 0.1},
                {"body": "ship", "dof": "pitch", "amplitude": 0.004, "frequency": 0.1,
                 "phase_deg": 90.0},
                {"point": "anc", "direction": [0, 0, 1], "amplitude": 0.05, "frequency": 0.1,
                 "phase_deg": -60.0},
            ]  # fmt: skip
            if method == "time":
                dyn = time_domain(exc, elements=elements, steps=64, periods=30)
            else:
                dyn = {"excitation": exc, "method": "frequency", "elements": elements}
            study["analysis"]["dynamic"] = dyn
            ds = run(tmp_path, study)
            assert np.all(ds["status"] == 0), ds["message"].values
            assert contract_problems(ds, dynamic=True) == []
            assert str(ds["dynamic_method"].item()) == method
            runs[method] = ds
        fd, td = runs["frequency"], runs["time"]
        assert float(fd["laid_length"].max()) == 0.0
        static = fd["tension_b"].values
        worst[elements] = max(
            float(np.max(np.abs(fd[n].values - td[n].values) / static)) for n in ENDS
        )
        # the ship's force and moment extremes alike (measured 1e-3 of the largest
        # static force component at 10 elements, 3e-4 at 20; moments over 10 m of arm)
        scale = float(np.abs(fd["body_force"].sel(dof=["surge", "sway", "heave"])).max())
        arm = np.array([1.0, 1.0, 1.0, 10.0, 10.0, 10.0])
        for n in ("body_force_max", "body_force_min"):
            diff = np.abs(fd[n] - td[n]).sel(body="ship").values / arm
            assert diff.max() < 2e-3 * scale, (elements, n, diff / scale)
    assert worst[10] < 5e-3 and worst[20] < 1.2e-3, worst
    assert worst[20] < worst[10] / 3.0, worst


@pytest.mark.parametrize("method", ["time", "frequency"])
def test_a_turned_body_pitches_about_its_own_axis(tmp_path: Path, method: str) -> None:
    """The 3-leg spread pitched at 0.1 Hz (0.1 rad in the time domain, 0.002 rad in the
    frequency domain), against the spread turned 40 deg about z whose fairleads are
    given in the body frame as before and whose body is yawed 40 deg
    (docs/guide/systems.md: R = Rz(yaw) Ry(pitch) Rx(roll), so the pitch turns about
    the yawed body's own y axis): the same system in a turned frame, every line's
    tension extremes equal (the turned coordinates' rounding through the Newton solves
    and the drag iteration: 1e-7 of the tension; measured 4e-12 (time), 1e-10
    (frequency)), and the body's heave force and yaw moment, which do not turn. The
    frequency domain moved a body's points by Theta x a with the angles' changes taken
    as a global rotation vector: it pitched the yawed body about the global y axis
    (legs 2 and 3 at 53 N and 10 N of amplitude instead of 28 N each; now
    cablestudy/dynamics/body_rates.py)."""
    if method == "time":
        block = (
            "  dynamic:\n    excitation: {body: hull, dof: pitch, amplitude: 0.1, "
            "frequency: 0.1}\n    method: time\n    elements: 8\n    points_per_period: 32\n"
            "    max_periods: 12\n"
        )
    else:
        block = (
            "  dynamic:\n    excitation: {body: hull, dof: pitch, amplitude: 0.002, "
            "frequency: 0.1}\n    method: frequency\n    elements: 8\n"
        )
    plain = yaml.safe_load(spread(f"pitch0_{method}", analysis=block))
    turned = yaml.safe_load(spread(f"pitch40_{method}", turn_deg=40.0, analysis=block))
    for k, v in turned["points"].items():
        if v["kind"] == "body":
            v["offset"] = plain["points"][k]["offset"]
    turned["bodies"]["hull"]["position"][5] = float(np.deg2rad(40.0))
    a, b = run(tmp_path, plain), run(tmp_path, turned)
    for ds in (a, b):
        assert np.all(ds["status"] == 0) and contract_problems(ds, dynamic=True) == []
        assert statics_problems(ds) == []
    big = float(a["tension_max_b"].max())
    for name in (*ENDS, "tension_mean_a", "tension_mean_b"):
        np.testing.assert_allclose(b[name].values, a[name].values, rtol=0, atol=1e-6 * big)
    for name in ("body_force_max", "body_force_min"):
        for dof in ("heave", "yaw"):
            np.testing.assert_allclose(
                b[name].sel(dof=dof).values, a[name].sel(dof=dof).values, rtol=0,
                atol=1e-6 * big * 10.0,  # a moment: forces times the 10 m fairlead radius
            )  # fmt: skip


def test_two_spectra_of_one_wave_move_the_body_coherently(tmp_path: Path) -> None:
    """A body surged by a JONSWAP sea times an RAO, given as two entries of the same
    wave (RAO r, seed 3, 16 lines), against one entry of RAO 2 r: the motion of each
    degree of freedom is the one wave's realisation times its RAO (the same seeded
    phases), so the two studies move the body alike and every tension is equal to the
    rounding of summing two halves (1e-9 of the tension)."""
    wave = {"hs": 2.0, "tp": 10.0}
    rao = [[0.0, 1.0], [0.1, 1.0], [0.2, 0.5], [0.3, 0.1]]

    def study(name: str, excitation: object) -> dict:
        s = yaml.safe_load(spread(name))
        dyn = time_domain(excitation)
        dyn.pop("max_periods")
        dyn["duration"] = 60.0
        s["analysis"]["dynamic"] = dyn
        return s

    entry = {"body": "hull", "dof": "surge", "wave_spectrum": wave, "components": 16, "seed": 3}
    double = run(tmp_path, study("rao2", {**entry, "rao": [[f, 2.0 * a] for f, a in rao]}))
    halves = run(tmp_path, study("raos", [{**entry, "rao": rao}, {**entry, "rao": rao}]))
    for ds in (double, halves):
        assert np.all(ds["status"] == 0) and contract_problems(ds, dynamic=True) == []
        assert str(ds["dynamic_method"].item()) == "time"
    big = float(double["tension_max_b"].max())
    for name in ENDS:
        np.testing.assert_allclose(
            halves[name].values, double[name].values, rtol=0, atol=1e-9 * big
        )


def test_a_free_points_added_mass_is_mass_that_does_not_weigh(tmp_path: Path) -> None:
    """The bridle's clump (300 kg added mass) and buoy (4000 kg), surged 0.1 m at
    0.1 Hz, against the same points with that added mass as mass and the volume that
    buoys its weight (V + m_a / rho): the same inertia and the same net weight, so both
    methods give the same tensions (to the rounding of the weights: 1e-9)."""
    exc = {"body": "ship", "dof": "surge", "amplitude": 0.1, "frequency": 0.1}
    for method in ("frequency", "time"):
        got = {}
        for kind in ("added", "massive"):
            study = bridle(f"{kind}_{method}")
            if kind == "massive":
                for p in ("clump", "buoy"):
                    pt = study["points"][p]
                    pt["mass"] += pt["added_mass"]
                    pt["volume"] += pt.pop("added_mass") / 1025.0
            if method == "time":
                study["analysis"]["dynamic"] = time_domain(exc, elements=6, periods=8)
            else:
                study["analysis"]["dynamic"] = {"excitation": exc, "method": method, "elements": 6}
            ds = run(tmp_path, study)
            assert np.all(ds["status"] == 0) and contract_problems(ds, dynamic=True) == []
            got[kind] = ds
        big = float(got["added"]["tension_max_b"].max())
        for name in ENDS:
            np.testing.assert_allclose(
                got["massive"][name].values, got["added"][name].values, rtol=0, atol=1e-9 * big
            )


#: (case, the excitation of the dynamic spread, the field named, words the message holds,
#: words it must not hold)
BAD = [
    (
        "body spectrum along a direction",
        {"body": "hull", "dof": "surge", "spectrum": [[0.05, 1.0], [0.2, 1.0]],
         "direction": [1, 0, 0]},
        "analysis.dynamic.excitation.direction",
        ["[1, 0, 0]", "degree of freedom (dof)", "remove direction"],
        ["must be None"],
    ),
    (
        "body spectrum at a line end",
        {"body": "hull", "dof": "surge", "spectrum": [[0.05, 1.0], [0.2, 1.0]], "end": "b"},
        "analysis.dynamic.excitation.end",
        ["'b'", "not a line end", "remove end"],
        ["must be None"],
    ),
    (
        "point spectrum at a line end",
        {"point": "a1", "direction": [0, 0, 1], "spectrum": [[0.05, 1.0], [0.2, 1.0]],
         "end": "a"},
        "analysis.dynamic.excitation.end",
        ["'a'", "not a line end", "remove end"],
        ["must be None"],
    ),
    # was: "unknown key 'amplitude' (did you mean 'amplitude'?); allowed keys here:
    # amplitude, body, ..." (the keys of every kind of motion)
    (
        "amplitude on a body spectrum",
        {"body": "hull", "dof": "surge", "spectrum": [[0.05, 1.0], [0.2, 1.0]], "amplitude": 1.0},
        "analysis.dynamic.excitation.amplitude",
        ["unknown key 'amplitude'", "allowed keys here: body, components, dof, rao, seed, "
         "spectrum, storm_duration, wave_spectrum", "(got 1.0)"],
        ["did you mean", "direction", "phase_deg"],
    ),
    # was named at 'analysis.dynamic.excitation.BodySpectrum' (an internal tag)
    (
        "waves without the motion's rao",
        {"body": "hull", "dof": "heave", "wave_spectrum": {"hs": 2.0, "tp": 10.0}},
        "analysis.dynamic.excitation",
        ["wave_spectrum together with rao", "'wave_spectrum'"],
        ["BodySpectrum"],
    ),
]  # fmt: skip


@pytest.mark.parametrize(
    ("case", "excitation", "field", "words", "not_words"), BAD, ids=[b[0] for b in BAD]
)
def test_bad_system_motions_are_refused_in_words(
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
    case: str,
    excitation: dict,
    field: str,
    words: list[str],
    not_words: list[str],
) -> None:
    """Motions a user plausibly writes wrong are refused before any work, naming the
    field (as a path into the study file), the value and what to do; the message does
    not contradict itself nor name internals."""
    study = yaml.safe_load(spread("badmotion"))
    dyn = time_domain(excitation)
    dyn.pop("max_periods")
    dyn["duration"] = 60.0
    study["analysis"]["dynamic"] = dyn
    cfg = tmp_path / "badmotion.yaml"
    cfg.write_text(yaml.safe_dump(study, sort_keys=False))
    code = main(["run", str(cfg), "--out", str(tmp_path), "--no-cache", "--no-progress"])
    err = capsys.readouterr().err
    assert code == 2 and not (tmp_path / "badmotion.nc").exists(), case
    assert f": {field}: " in err, err
    for w in words:
        assert w in err, (w, err)
    for w in not_words:
        assert w not in err, (w, err)


def test_auto_per_case_amplitudes_only_where_the_frequency_domain_ran(tmp_path: Path) -> None:
    """The 3-leg spread under method auto, surged 0.02 m and 4 m: the small motion is
    linear (the frequency domain, its reason 'auto: linear ...'), the large one slackens
    leg 1 (the time domain, its reason naming line 'l1'). tension_amplitude_a/_b hold
    numbers where the frequency domain ran and NaN where it did not, and the variable
    says what that NaN means (a NaN at status 0 without a word was left to the user to
    guess)."""
    text = spread(
        "autosweep",
        analysis=(
            "  dynamic:\n"
            "    excitation: {body: hull, dof: surge, amplitude: 2.0, frequency: 0.1}\n"
            "    method: auto\n    elements: 8\n    points_per_period: 32\n"
            "    max_periods: 12\n"
        ),
        sweep="  analysis.dynamic.excitation.amplitude: [0.02, 4.0]\n",
    )
    ds = run_study(tmp_path, text)
    assert np.all(ds["status"] == 0) and contract_problems(ds, dynamic=True) == []
    assert list(ds["dynamic_method"].values) == ["frequency", "time"]
    reasons = [str(r) for r in ds["dynamic_method_reason"].values]
    assert reasons[0].startswith("auto: linear") and "'l1'" in reasons[1], reasons
    for e in "ab":
        amp = ds[f"tension_amplitude_{e}"]
        assert amp.dims == ("amplitude", "line") and amp.attrs["units"] == "N"
        assert bool(np.isfinite(amp.sel(amplitude=0.02)).all())
        assert bool(np.isnan(amp.sel(amplitude=4.0)).all())
        assert "time domain" in amp.attrs.get("nan_means", ""), amp.attrs


def test_a_spread_yawed_or_rolled_through_large_angles_keeps_its_symmetry(
    tmp_path: Path,
) -> None:
    """The 3-leg spread (legs at 0, 120, 240 deg) yawed 0.3 rad at 0.1 Hz: the
    120-degree symmetry holds at every instant (yaw about the centre turns each
    fairlead alike), so the three legs' extremes are equal; rolled 0.15 rad, legs 2 and
    3 are mirror images in y (roll +r mirrored is roll -r, the same motion half a
    period later): their extremes are equal, leg 1 (in the x-z plane) apart. Equal to
    the steady-state tolerance (2e-3 of each line's range) as the runs settle; measured
    far closer (the same arithmetic up to the fairleads' rounded coordinates)."""
    block = (
        "  dynamic:\n    excitation: {body: hull, dof: %s, amplitude: %s, frequency: 0.1}\n"
        "    method: time\n    elements: 8\n    points_per_period: 32\n    max_periods: 12\n"
    )
    yawed = run_study(tmp_path, spread("yawed", analysis=block % ("yaw", 0.3)))
    rolled = run_study(tmp_path, spread("rolled", analysis=block % ("roll", 0.15)))
    for ds in (yawed, rolled):
        assert np.all(ds["status"] == 0) and contract_problems(ds, dynamic=True) == []
    span = float((yawed["tension_max_b"] - yawed["tension_min_b"]).min())
    assert span > 1e3  # the yaw loads the legs
    for name in ENDS:
        t = yawed[name].values
        assert np.abs(t - t[0]).max() < 2e-3 * span, (name, t)
    span = float((rolled["tension_max_b"] - rolled["tension_min_b"]).sel(line="l2"))
    for name in ENDS:
        t = rolled[name]
        assert abs(float(t.sel(line="l2") - t.sel(line="l3"))) < 2e-3 * span, name


def test_a_held_spread_laid_on_a_rough_slope_stays_at_its_static_state(
    tmp_path: Path,
) -> None:
    """Two legs laid on a 3-degree slope with friction 0.6 (128 m and 170 m on the
    seabed), anchors on the slope, held still after statics by method discrete at the
    dynamic mesh: the seabed's plane, stiffness and friction of the dynamic model are
    the statics', so the end tensions stay at the static ones (Newton tolerance: 1e-5
    of the largest tension; measured 1e-7)."""
    from tests.integration.test_contract_external_system import SLOPE

    heights = (-300.0 * np.tan(np.deg2rad(-3.0)) - 100.0, 300.0 * np.tan(np.deg2rad(-3.0)) - 100.0)
    study = yaml.safe_load(SLOPE % tuple(repr(float(h)) for h in heights))
    study.pop("sweep")
    study["name"] = "slopeheld"
    study["analysis"] = {
        "static": {"nodes": 11, "method": "discrete"},
        "dynamic": time_domain(
            {"body": "hull", "dof": "surge", "amplitude": 0.0, "frequency": 0.1},
            elements=10,
            periods=6,
        ),
    }
    ds = run(tmp_path, study)
    assert np.all(ds["status"] == 0), ds["message"].values
    assert contract_problems(ds, dynamic=True) == []
    assert bool((ds["laid_length"] > 100.0).all())
    big = float(ds["tension_b"].max())
    for e in "ab":
        for m in ("max", "min"):
            diff = np.abs(ds[f"tension_{m}_{e}"] - ds[f"tension_{e}"]).values
            assert diff.max() < 1e-5 * big, (m, e, diff / big)
