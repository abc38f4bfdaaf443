"""The dynamics of a free point resting on the seabed: a chain split at a junction (or
a 2 t clump) lying on its laid part moves as the one line with that attachment at the
same arc length, through the command line to the netCDF file.

Same physics, same mesh: MoorPy's chain of 120 mm (as
tests/validation/test_system_moorpy_invariance.py) from an anchor at 200 m depth to a
fairlead at the surface 800 m away, cut at its middle; each half ``n`` elements in the
system and the one line ``2 n`` (two equal segments), so the nodes are at the same
places and the junction is the one line's node at the attachment. The junction's end
nodes carry the seabed's contact spring, damper and friction as every line node does,
and share the point's unknowns: the contact of the two half elements is the one line's
node's, with the point's weight on it.

Tolerances. Time domain: each step's Newton stops at a residual force of
``newton_tolerance`` (1e-7) of the largest static tension, which moves the tensions by
about as much relative to them; the two runs take the same steps, and their
differences, fed on over the run's hundred steps and damped by the line's drag, stay
within 1e-5 (a factor of a hundred over the run's accumulation, as
tests/integration/test_system_dynamics.py bounds bare junctions). Frequency domain:
both drag iterations stop when the velocity amplitudes change by less than 1e-6 of
the largest, so the tension amplitudes agree within a few 1e-6 of themselves and the
extremes within less relative to the static tension; 1e-5 bounds it. The floor is the
same comparison with the junction hanging 0.84 m above the seabed (a line 28 m
shorter): there the junction's drag and added mass take each line's own tangent
against the one line's chord, and it touches the seabed as the fairlead moves: measured
7.6e-5 (time) and 1.5e-6 (frequency). Resting on the seabed the junction hardly moves:
measured 5e-8 (2.8e-7 with the clump) in time and 7e-10 in frequency.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import yaml

from cablestudy.cli import main
from tests.system_contract import run_study

SEG = {"diameter": 0.216, "mass_per_length": 288.0, "axial_stiffness": 1232572089.6}
ENV = {"fluid": {"density": 1025.0}, "gravity": 9.81, "depth": 200.0}
ANCHOR, FAIR = [-800.0, 0.0, -200.0], [0.0, 0.0, 0.0]


def _pair(tmp_path: Path, length: float, mass: float | None, method: str, body: bool):
    """The one line and the split system, both run: their datasets."""
    dyn: dict = {"method": method, "elements": 10}
    if method == "time":
        dyn |= {"points_per_period": 32, "duration": 30.0, "ramp_periods": 1.0}
    half = {"length": length / 2, **SEG}
    line: dict = {"segments": [half, half]}
    pt: dict = {"kind": "free", "position": [ANCHOR[0] + length / 2, 0.0, -200.0]}
    if mass is not None:
        line["attachments"] = [{"s": length / 2, "mass": mass}]
        pt["mass"] = mass
    move = {"direction": [1.0, 0.0, 0.0], "amplitude": 3.0, "frequency": 0.1}
    one = {"name": "one", "environment": ENV, "line": line}
    one["ends"] = {
        "a": {"kind": "fixed", "position": ANCHOR},
        "b": {"kind": "fixed", "position": FAIR},
    }
    dyn1 = {**dyn, "elements": 20, "excitation": {"end": "b", **move}}
    one["analysis"] = {"static": {"nodes": 21}, "dynamic": dyn1}
    points = {"a": one["ends"]["a"], "m": pt, "f": {"kind": "fixed", "position": FAIR}}
    excitation: dict = {"point": "f", **move}
    two: dict = {"name": "two", "environment": ENV, "points": points}
    if body:  # the fairlead on a prescribed body surged as the one line's end
        points["f"] = {"kind": "body", "body": "ship", "offset": FAIR}
        two["bodies"] = {"ship": {"kind": "prescribed"}}
        excitation = {"body": "ship", "dof": "surge", "amplitude": 3.0, "frequency": 0.1}
    two["lines"] = {
        k: {"a": a, "b": b, "segments": [half]} for k, a, b in (("l1", "a", "m"), ("l2", "m", "f"))
    }
    two["analysis"] = {"static": {"nodes": 21}, "dynamic": {**dyn, "excitation": excitation}}
    return tuple(run_study(tmp_path, yaml.safe_dump(s, sort_keys=False)) for s in (one, two))


def _gap(tmp_path: Path, length: float, mass: float | None, method: str, body: bool) -> float:
    """The largest relative difference of the fairlead's tension extremes, the split
    against the one line (both solved by the same method)."""
    one, two = _pair(tmp_path, length, mass, method, body)
    assert int(one["status"]) == 0 and int(two["status"]) == 0, str(two["message"].values)
    assert (float(two["point_position"].values[0, 2]) == -200.0) == (length == 888.0)
    assert str(two["dynamic_method"].values) == str(one["dynamic_method"].values)
    if method == "auto":  # its checks pass both (the laid line moves 3 m): linear
        assert str(two["dynamic_method"].values) == "frequency"
    return max(
        abs(float(two[f"{k}_b"].values[1]) / float(one[k].values) - 1.0)
        for k in ("tension_max", "tension_min")
    )


@pytest.mark.parametrize(
    ("mass", "method", "body"),
    [
        (None, "time", False),
        (2000.0, "time", False),
        (None, "time", True),
        (None, "frequency", False),
        (2000.0, "frequency", True),
        (2000.0, "auto", False),
    ],
)
def test_a_point_resting_on_the_seabed_moves_as_the_one_line_with_its_attachment(
    tmp_path: Path, mass: float | None, method: str, body: bool
) -> None:
    assert _gap(tmp_path, 888.0, mass, method, body) <= 1e-5


@pytest.mark.parametrize("method", ["time", "frequency"])
def test_resting_the_split_is_no_further_from_the_one_line_than_hanging(
    tmp_path: Path, method: str
) -> None:
    """The floor: the same comparison with the junction hanging 0.84 m above the seabed
    (measured 7.6e-5 time, 1.5e-6 frequency) bounds the resting one's."""
    assert _gap(tmp_path, 888.0, None, method, False) <= _gap(tmp_path, 860.0, None, method, False)


def _moordyn_fairlead(path: Path, periods: int = 6, samples: int = 1000) -> tuple[float, float]:
    """MoorDyn on the exported file, its coupled body surged as the study's (3 m, 0.1 Hz,
    ramped over two periods by (1 - cos(pi t / t_r)) / 2), handed over ``samples`` times
    a period with the secant velocity: the fairlead's largest and smallest tension over
    the last period, extrapolated to the end from the two end segments (1.5 T_0 - 0.5 T_1,
    as benchmarks/make_moordyn_system_refs.py takes them)."""
    import moordyn

    dt, t_r = 10.0 / samples, 20.0

    def q(t: float) -> np.ndarray:
        r = 0.5 * (1.0 - np.cos(np.pi * t / t_r)) if t < t_r else 1.0
        return np.array([3.0 * r * np.sin(0.2 * np.pi * t), 0, 0, 0, 0, 0], dtype=float)

    system = moordyn.Create(str(path))
    moordyn.Init(system, q(0.0), np.zeros(6))
    line = moordyn.GetLine(system, 2)
    n = moordyn.GetLineN(line)
    seen = []
    for k in range(periods * samples):
        moordyn.Step(system, q(k * dt), (q((k + 1) * dt) - q(k * dt)) / dt, k * dt, dt)
        t_n, t_m = (np.asarray(moordyn.GetLineNodeTen(line, j)) for j in (n, n - 1))
        seen.append(1.5 * np.linalg.norm(t_n) - 0.5 * np.linalg.norm(2.0 * t_m - t_n))
    moordyn.Close(system)
    last = seen[-samples:]
    return max(last), min(last)


def test_the_resting_clump_against_moordyn(tmp_path: Path) -> None:
    """The body-driven split with the 2 t clump resting on the seabed, exported by
    ``cablestudy export moordyn`` and run by MoorDyn (its lines' seabed contact acts on
    their end nodes at the point, which carry the point's weight), against ours at 20
    elements a line and 64 steps a period: the fairlead's extremes within 1e-2 of the
    largest (the bar of tests/validation/test_system_dynamics_moordyn.py: the issue's
    2 %, halved). Measured 5e-4 (971.3 and 841.7 kN against MoorDyn's 971.0 and 842.2):
    MoorDyn at the exported 20 segments is within 8e-4 of itself at 80, ours at 20
    within 1e-3 of ours at 40 elements and 128 steps; the hand-over every 1/1000 period
    moves MoorDyn's extremes by 2e-3 from every 1/200 (its coupled motion's kinks)."""
    one, two = _pair(tmp_path, 888.0, 2000.0, "time", True)
    study = yaml.safe_load(two.attrs["study_yaml"])
    dyn = study["analysis"]["dynamic"]
    for key in ("duration", "ramp_periods"):
        del dyn[key]
    dyn |= {"elements": 20, "points_per_period": 64}
    ours = run_study(tmp_path, yaml.safe_dump(study | {"name": "ours"}, sort_keys=False))
    assert int(ours["status"]) == 0 and float(ours["point_position"].values[0, 2]) == -200.0
    args = ["export", "moordyn", str(tmp_path / "ours.yaml"), "--out", str(tmp_path / "md.dat")]
    assert main(args) == 0
    theirs = _moordyn_fairlead(tmp_path / "md.dat")
    mine = float(ours["tension_max_b"].values[1]), float(ours["tension_min_b"].values[1])
    np.testing.assert_allclose(mine, theirs, rtol=0.0, atol=1e-2 * theirs[0])
