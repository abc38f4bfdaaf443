"""Validation of the time-domain line model's bending and seabed terms against exact
solutions and invariances: the tensioned beam's static deflection (Euler-Bernoulli with
tension, pinned ends), a chain mooring resting on a frictional seabed that stays still
when nothing moves it, the mirror invariance of a sloped seabed, and a towed free end
that settles where the static towing solution puts it."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import xarray as xr
import yaml

from cablestudy.cli import main
from cablestudy.dynamics.assembly import evaluate
from cablestudy.dynamics.discrete_line import DynamicExtras, discretise
from cablestudy.dynamics.model import static_equilibrium
from cablestudy.statics.base import Medium

from ..line_models import one_segment

G = 9.80665


def beam(
    n: int, *, span: float, q: float, tension: float, ei: float
) -> tuple[np.ndarray, np.ndarray, float]:
    """Node positions x [m] and deflections [m] of the discrete model of a horizontal
    tensioned beam with pinned ends under its weight q [N/m], and its horizontal
    tension [N]."""
    ea = 1e10
    length = span / (1.0 + tension / ea)
    model = one_segment(
        length=length, weight=q, mass=q / G, axial_stiffness=ea, bending_stiffness=ei
    )
    disc = discretise(model, Medium(density=0.0, gravity=G), n, DynamicExtras())
    x0 = np.stack([np.linspace(0.0, span, n + 1), np.zeros(n + 1), np.zeros(n + 1)], 1)
    # tolerance: 1e-7 of the tension, above the rounding of EA (l / l0 - 1) ~ 4e-5 N
    x, _, res, ok, _ = static_equilibrium(disc, x0, tolerance=1e-7 * tension)
    assert ok, res
    work = evaluate(disc, x, np.zeros_like(x))
    d = x[n // 2 + 1] - x[n // 2]
    return x[:, 0], -x[:, 2], float(work.tension[n // 2] * d[0] / np.linalg.norm(d))


def exact_deflection(
    s: np.ndarray, *, span: float, q: float, tension: float, ei: float
) -> np.ndarray:
    """EI w'''' - T w'' = q with w = w'' = 0 at both ends (pinned):
    w = q/T [s (L - s)/2 + (cosh(k (s - L/2)) / cosh(kL/2) - 1) / k^2], k = sqrt(T/EI)."""
    k = math.sqrt(tension / ei)
    shape = np.cosh(k * (s - span / 2.0)) / math.cosh(k * span / 2.0) - 1.0
    return q / tension * (s * (span - s) / 2.0 + shape / k**2)


def test_tensioned_beam_deflection_converges_to_the_exact_solution_as_h_squared() -> None:
    """kL = 5: tension and bending both matter (bending takes a third off the string's
    sag here). Lumped loads and second differences make the deflection converge as h^2:
    the largest nodal error must fall by 4 +- 0.5 per halving of the elements, and be
    below 1e-3 of the midspan deflection at 40 elements."""
    span, q, tension = 10.0, 100.0, 1.0e4
    ei = tension / 0.25  # k = 0.5 1/m
    errors = []
    for n in (10, 20, 40):
        x, w, h = beam(n, span=span, q=q, tension=tension, ei=ei)
        exact = exact_deflection(x, span=span, q=q, tension=h, ei=ei)
        errors.append(float(np.abs(w - exact).max() / exact.max()))
    string = q * span**2 / (8.0 * tension)
    exact_mid = exact_deflection(np.array([span / 2]), span=span, q=q, tension=tension, ei=ei)[0]
    assert exact_mid < 0.8 * string  # bending matters: the string alone sags more
    ratios = [errors[0] / errors[1], errors[1] / errors[2]]
    assert all(3.5 < r < 4.5 for r in ratios), (errors, ratios)
    assert errors[-1] < 1e-3


CHAIN = """
name: chain
environment:
  fluid: water
  depth: 200.0
  seabed: {friction: 0.5, slope_deg: 0.0, slope_heading_deg: 0.0}
line:
  segments:
    - {length: 800.0, diameter: 0.1533, mass_per_length: 141.0, axial_stiffness: 6.0e8,
       drag_normal: 2.4, drag_tangential: 1.15}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -200.0]}
  b: {kind: fixed, position: [750.0, 0.0, -10.0]}
analysis:
  static: {nodes: 41}
  dynamic:
    excitation: {end: b, direction: [1.0, 0.0, 0.0], amplitude: 0.0, frequency: 0.1}
    method: time
    elements: 40
"""


def _run(tmp_path: Path, data: dict, name: str) -> xr.Dataset:
    data = {**data, "name": name}
    cfg = tmp_path / f"{name}.yaml"
    cfg.write_text(yaml.safe_dump(data))
    assert main(["run", str(cfg), "--out", str(tmp_path), "--scheduler", "synchronous"]) == 0
    return xr.load_dataset(tmp_path / f"{name}.nc")


def test_a_laid_chain_with_friction_stays_still_when_nothing_moves_it(tmp_path: Path) -> None:
    """800 m of chain, 312 m of it laid on a frictional seabed, run for its full window
    with zero excitation: the friction anchors hold the static friction, so the end
    tension stays at its static value to the Newton tolerance (1e-6 of the tension per
    node, so the end force moves by at most a few 1e-6 relative): no creep."""
    ds = _run(tmp_path, yaml.safe_load(CHAIN), "chain-still")
    assert int(ds["status"]) == 0, str(ds["message"].values)
    assert float(ds["laid_length"]) > 250.0
    static = float(ds["tension_static"])
    assert float(ds["periods"]) >= 3
    spread = float(ds["tension_max"]) - float(ds["tension_min"])
    assert spread <= 5e-6 * static
    # the discrete start carries the continuous static fairlead tension to the lumping
    # error O((h / L)^2) with 40 elements ~ 1e-3
    assert abs(static - float(ds["tension_b"])) <= 2e-3 * static


def test_a_sloped_seabed_gives_the_mirrored_result_under_mirrored_geometry(
    tmp_path: Path,
) -> None:
    """The chain on a seabed rising 3 deg towards +x, fairlead moved in surge, against the
    same chain mirrored through x = 0 (anchor at +x, seabed rising towards -x, motion
    along -x): the same tensions to the solver tolerances (Newton 1e-6 of the tension,
    an identical step sequence up to rounding)."""
    base = yaml.safe_load(CHAIN)
    base["environment"]["seabed"]["slope_deg"] = 3.0
    base["environment"]["depth"] = 200.0
    base["ends"]["a"]["position"] = [0.0, 0.0, -200.0]
    base["ends"]["b"]["position"] = [750.0, 0.0, -10.0]
    base["analysis"]["dynamic"]["excitation"]["amplitude"] = 2.0
    mirror = yaml.safe_load(yaml.safe_dump(base))
    mirror["environment"]["seabed"]["slope_heading_deg"] = 180.0
    mirror["ends"]["a"]["position"] = [0.0, 0.0, -200.0]
    mirror["ends"]["b"]["position"] = [-750.0, 0.0, -10.0]
    mirror["analysis"]["dynamic"]["excitation"]["direction"] = [-1.0, 0.0, 0.0]
    one = _run(tmp_path, base, "slope")
    two = _run(tmp_path, mirror, "slope-mirror")
    for ds in (one, two):
        assert int(ds["status"]) == 0, str(ds["message"].values)
    for var in ("tension_static", "tension_max", "tension_min"):
        a, b = float(one[var]), float(two[var])
        assert abs(a - b) <= 1e-5 * a, (var, a, b)
    assert float(one["tension_max"]) > 1.05 * float(one["tension_static"])  # it did move


def test_a_towed_free_end_settles_on_the_static_towing_solution() -> None:
    """A towing line: end B fixed (the tug), end A free carrying a constant force (the
    towed body's drag and weight). The tug end is moved by 1 m along x (a time table,
    held after 4 s) in water: the free end is dragged along and settles, with drag
    dying out, on the static towing solution translated by the same 1 m, so the end
    tension returns to the static value (to the steady tolerance 1e-3 and Newton's
    1e-6) after having changed while it moved."""
    data = {
        "environment": {"fluid": "water"},
        "line": {
            "segments": [
                {
                    "length": 50.0,
                    "diameter": 0.03,
                    "mass_per_length": 2.0,
                    "axial_stiffness": 5.0e6,
                }
            ]
        },
        "ends": {
            "a": {"kind": "force", "force": [-300.0, 0.0, -200.0]},
            "b": {"kind": "fixed", "position": [0.0, 0.0, 0.0]},
        },
        "analysis": {
            "static": {"method": "catenary", "nodes": 21},
            "dynamic": {
                "excitation": {
                    "end": "b",
                    "direction": [1.0, 0.0, 0.0],
                    "table": [[0.0, 0.0], [2.0, 0.5], [4.0, 1.0], [6.0, 1.0]],
                },
                "method": "time",
                "elements": 20,
                "duration": 200.0,
                "ramp_periods": 0.0,
            },
        },
    }
    from .dynamics_helpers import run_direct

    data["name"] = "towed"
    res, line, x_static = run_direct(data)
    assert res.status == 0, res.message
    assert not line.held[0] and line.held[-1]
    x_end = res.record["x"][-1]
    moved = x_static + np.array([1.0, 0.0, 0.0])
    settle = float(np.abs(x_end - moved).max())
    assert settle <= 2e-3, settle
    force = res.record["end_force"]
    np.testing.assert_allclose(force[-1, 1], force[0, 1], rtol=1e-3)
    assert np.abs(force[:, 1] - force[0, 1]).max() > 1e-3 * np.linalg.norm(force[0, 1])


def test_seabed_friction_dissipates_energy_and_never_adds_it() -> None:
    """The laid chain, its fairlead moved 8 m in surge at 0.05 Hz so that the laid
    chain near touchdown slides back and forth. Per step the stick-slip law's work
    on the nodes, W = f_(n+1) . (x_(n+1) - x_n), is at most minus the change of the
    energy stored in the friction springs (|f|^2 / 2 k per node): the elastic part is
    returned at most, the sliding part opposes the slip. So the dissipation
    D = -sum W - E_spring never falls below zero (to rounding: 1e-9 of the largest
    friction work per step) and grows where the chain slides."""
    from .dynamics_helpers import run_direct

    data = yaml.safe_load(CHAIN)
    dyn = data["analysis"]["dynamic"]
    dyn["excitation"].update(amplitude=8.0, frequency=0.05)
    dyn.update(duration=60.0, ramp_periods=0.5, elements=40)
    res, line, _ = run_direct(data)
    assert res.status == 0, res.message
    x = res.record["x"]
    f = res.record["friction"]
    k = np.maximum(line.seabed_stiffness, 1e-300)[None, :]
    work = np.einsum("tia,tia->t", f[1:], np.diff(x, axis=0))
    stored = np.sum(np.einsum("tia,tia->ti", f, f) / (2.0 * k), axis=1)
    dissipated = -np.cumsum(work) - (stored[1:] - stored[0])
    scale = float(np.abs(work).max())
    assert dissipated.min() >= -1e-9 * scale * len(work), dissipated.min()
    assert dissipated[-1] > 20.0 * scale  # the chain slid: friction took energy out
