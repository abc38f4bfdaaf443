"""Random study generator and solver-independent checks (the stress helper's harness).

Written from the study-file contract (docs/reference/keys.md, docs/guide/*.md,
docs/conventions.md), not from the solvers: :func:`generate` makes a seeded,
deterministic, valid-looking study (a one-line study, static or dynamic, or a system of
lines joined at a free point or on a body); :mod:`tests.stress_checks` runs it through
the command line (``cablestudy run STUDY --out DIR``) and checks every case against what
a user can recompute from the written dataset:

* the run: exit 0 (some case ok), 3 (none ok) or 2 (refused, with a message naming the
  field); never 1, never a Python traceback, never numpy's RuntimeWarning;
* a case of status 0 (statics): finite outputs, the end positions of the study, the
  stretched distance between neighbouring nodes no longer than their stretched arc
  length, tension >= 0 (no bending), the whole line's balance of forces where the loads
  are known (no current: weight, attachments, seabed reaction vertical when frictionless
  and flat), the horizontal tension constant along a uniform catenary with no current,
  friction, slope or attachments;
* a case of status 0 (dynamics): tension_max >= tension_mean >= tension_min, finite;
* a failed case: a message, NaN in the failed analysis's outputs (status 10 and 11 keep
  their numbers, docs/conventions.md), the statics kept when only the dynamics failed.

Each anomaly is a (kind, text) pair; the kinds are counted by the batch driver
(``benchmarks/stress_random.py``) and the fixed-seed test
(``tests/integration/test_stress_random_studies.py``) asserts there are none.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

GRAVITY = 9.80665
WATER = 1025.0

#: material families: (mass per length / d^2 [kg/m/m^2], EA / d^2 [N/m^2], Cdn)
#: from the usual rules of thumb (chain ~ 19.9 d^2 t/m, wire ~ 5 d^2 t/m, polyester
#: ~ 0.8 d^2 t/m with the chain's 0.85e11 d^2, wire's 9e10 d^2, polyester's 1.1e9 d^2)
MATERIALS = {
    "chain": (19900.0, 0.854e11, 2.4),
    "wire": (5000.0, 9.0e10, 1.2),
    "polyester": (800.0, 1.1e9, 1.2),
}


def _r(rng: np.random.Generator, lo: float, hi: float) -> float:
    return float(rng.uniform(lo, hi))


def _log(rng: np.random.Generator, lo: float, hi: float) -> float:
    return float(math.exp(rng.uniform(math.log(lo), math.log(hi))))


def _round(x: float, digits: int = 6) -> float:
    """A number as a user writes it (6 significant digits)."""
    if x == 0.0 or not math.isfinite(x):
        return float(x)
    return float(f"{x:.{digits}g}")


def _segment(rng: np.random.Generator, length: float, rho: float, extreme: bool) -> dict:
    kind = str(rng.choice(list(MATERIALS)))
    mass_d2, ea_d2, cdn = MATERIALS[kind]
    d = _log(rng, 0.01, 0.2)
    mass = mass_d2 * d * d
    ea = ea_d2 * d * d
    if extreme:
        ea = _log(rng, 1e3, 1e11)
        roll = rng.uniform()
        if roll < 0.25 and rho > 0:  # slightly buoyant
            mass = rho * math.pi * d * d / 4 * _r(rng, 0.8, 0.99)
        elif roll < 0.5:  # heavy
            mass = mass * _r(rng, 2.0, 20.0)
    seg = {
        "length": _round(length),
        "diameter": _round(d),
        "mass_per_length": _round(mass),
        "axial_stiffness": _round(ea),
        "drag_normal": cdn,
        "drag_tangential": 0.01 if kind != "chain" else 0.4,
    }
    return seg


def _weight(seg: dict, rho: float) -> float:
    """Submerged weight per length [N/m] (docs: weight_in_fluid overrides)."""
    if "weight_in_fluid" in seg:
        return float(seg["weight_in_fluid"])
    a = math.pi * seg["diameter"] ** 2 / 4
    return (seg["mass_per_length"] - rho * a) * GRAVITY


@dataclass
class Meta:
    """What the checks need to know of a generated study."""

    kind: str  # "line" | "system"
    method: str
    rho: float
    depth: float | None
    slope: float = 0.0
    friction: float = 0.0
    current: bool = False
    attachments: bool = False
    bending: bool = False
    dynamic: str | None = None  # method of analysis.dynamic
    ends: tuple[str, str] = ("fixed", "fixed")
    expect_refusal: str | None = None  # a key the study gives that should be refused
    sweep_dim: str | None = None
    notes: list[str] = field(default_factory=list)


def _current(rng: np.random.Generator, depth: float) -> list[dict]:
    n = int(rng.integers(1, 4))
    zs = sorted((-_r(rng, 0.0, depth) for _ in range(n - 1)), reverse=True)
    zs = [0.0] + zs
    return [
        {
            "z": _round(z),
            "speed": _round(_r(rng, 0.05, 2.0)),
            "heading_deg": _round(_r(rng, -180, 180)),
        }
        for z in zs
    ]


def _makeup(rng: np.random.Generator, total: float, rho: float, extreme: bool) -> list[dict]:
    n = int(rng.integers(1, 5))
    parts = rng.dirichlet(np.ones(n)) * total
    parts = np.maximum(parts, total * 0.02)
    parts *= total / parts.sum()
    return [_segment(rng, float(p), rho, extreme) for p in parts]


def generate(seed: int, dynamic: bool = False) -> tuple[dict, Meta]:
    """One random study (a dict ready for yaml) and what the checks need about it;
    ``dynamic``: a one-line study with analysis.dynamic (a focused batch)."""
    rng = np.random.default_rng(seed)
    roll = 0.9 if dynamic else rng.uniform()
    if roll < 0.15:
        return _system(rng, seed)
    return _one_line(rng, seed, dynamic=roll > 0.75)


def _fluid(rng: np.random.Generator) -> tuple[Any, float]:
    r = rng.uniform()
    if r < 0.75:
        return "water", WATER
    if r < 0.85:
        return "vacuum", 0.0
    rho = _round(_r(rng, 800.0, 1100.0))
    return {"density": rho}, rho


def _one_line(rng: np.random.Generator, seed: int, dynamic: bool) -> tuple[dict, Meta]:
    fluid, rho = _fluid(rng)
    has_bed = rho > 0 and rng.uniform() < 0.8
    depth = _log(rng, 5.0, 3000.0)
    extreme = rng.uniform() < 0.35
    # geometry: anchor near the seabed (or the bottom of the span), fairlead near the top
    drop = depth * _r(rng, 0.3, 1.0)
    za = -depth if has_bed and rng.uniform() < 0.7 else -depth * _r(rng, 0.5, 1.0)
    zb = za + drop if rng.uniform() < 0.9 else za + drop * _r(rng, -0.2, 0.2)
    zb = min(zb, 0.0) if rho > 0 else zb
    zb = max(zb, -depth) if has_bed else zb
    span = max(abs(zb - za), 1.0) * _log(rng, 0.02, 20.0)
    chord = math.hypot(span, zb - za)
    length = chord * _r(rng, 0.98, 3.0)
    if has_bed and rng.uniform() < 0.3:  # enough to lay on the seabed
        length = max(length, (abs(zb - za) + span) * _r(rng, 0.7, 1.1))
    method = str(rng.choice(["catenary", "catenary", "shooting", "analytic", "discrete"]))
    segs = _makeup(rng, length, rho, extreme)
    if method == "analytic":  # a uniform line (the method's scope, docs/reference/keys.md)
        segs = [dict(segs[0], length=_round(length))]
    total = sum(s["length"] for s in segs)
    meta = Meta(kind="line", method=method, rho=rho, depth=depth if has_bed else None)
    env: dict[str, Any] = {"fluid": fluid}
    if has_bed:
        env["depth"] = _round(depth)
        meta.depth = env["depth"]
        bed: dict[str, Any] = {}
        if rng.uniform() < 0.4:
            bed["friction"] = _round(_r(rng, 0.0, 1.0))
            meta.friction = bed["friction"]
        if rng.uniform() < 0.2 and method in ("shooting", "catenary", "discrete"):
            bed["slope_deg"] = _round(_r(rng, -10.0, 10.0))
            meta.slope = bed["slope_deg"]
        if bed:
            env["seabed"] = bed
    if rho > 0 and method != "analytic" and rng.uniform() < 0.35:
        env["current"] = _current(rng, depth)
        meta.current = True
    line: dict[str, Any] = {"segments": segs}
    if method != "analytic" and rng.uniform() < 0.3:
        atts = []
        for _ in range(int(rng.integers(1, 3))):
            s = _round(_r(rng, 0.05, 0.95) * total)
            if rng.uniform() < 0.5:
                atts.append({"s": s, "mass": _round(_log(rng, 10.0, 1e4))})
            else:
                atts.append(
                    {"s": s, "volume": _round(_log(rng, 0.01, 5.0))}
                    if rho > 0
                    else {"s": s, "force": [0.0, 0.0, _round(_log(rng, 10, 1e4))]}
                )
        line["attachments"] = atts
        meta.attachments = True
    if method == "discrete" and rng.uniform() < 0.5:
        for s in segs:
            s["bending_stiffness"] = _round(_log(rng, 1.0, 1e5))
        meta.bending = True
    elif rng.uniform() < 0.03:  # a key the method cannot use: must be refused
        segs[0]["bending_stiffness"] = 100.0
        if method != "discrete":
            meta.expect_refusal = "bending_stiffness"
    ends: dict[str, Any] = {"a": {"kind": "fixed", "position": [0.0, 0.0, _round(za)]}}
    b_kind = "fixed"
    if method in ("catenary", "shooting", "discrete") and rng.uniform() < 0.3:
        b_kind = str(rng.choice(["force", "mooring"]))
    wsum = sum(max(_weight(s, rho), 0.0) * s["length"] for s in segs)
    if b_kind == "fixed":
        ends["b"] = {"kind": "fixed", "position": [_round(span), 0.0, _round(zb)]}
    elif b_kind == "force":
        h = wsum * _log(rng, 0.05, 5.0) + 1.0
        ends["b"] = {
            "kind": "force",
            "force": [_round(h), 0.0, _round(wsum * _r(rng, 0.2, 1.2) + 1.0)],
        }
    else:
        h = wsum * _log(rng, 0.05, 5.0) + 1.0
        ends["b"] = {"kind": "mooring", "force": [_round(h), 0.0], "z": _round(zb)}
    meta.ends = ("fixed", b_kind)
    nodes = int(rng.choice([11, 21, 51, 101]))
    analysis: dict[str, Any] = {"static": {"method": method, "nodes": nodes}, "time_limit": 60.0}
    if rng.uniform() < 0.2:
        analysis["modal"] = {
            "modes": int(rng.integers(1, 6)),
            "elements": int(rng.choice([10, 20, 40])),
        }
    # an excited mooring end is allowed (keys.md: only an unexcited one is refused)
    if dynamic and b_kind == "force":
        ends["b"] = {"kind": "fixed", "position": [_round(span), 0.0, _round(zb)]}
        ends["a"] = {"kind": "force", "force": [0.0, 0.0, -_round(wsum * _r(rng, 0.2, 1.2) + 1.0)]}
        meta.ends = ("force", "fixed")
    if dynamic:
        dyn_method = str(rng.choice(["time", "frequency", "auto"]))
        if meta.bending or meta.friction:
            pass
        freq = _round(_log(rng, 0.02, 1.0))
        exc: dict[str, Any]
        if dyn_method != "frequency" and rng.uniform() < 0.3:
            amp = _round(_log(rng, 0.01, 0.05) * chord)
            per = 1.0 / freq
            exc = {
                "end": "b",
                "direction": [1.0, 0.0, 0.0],
                "table": [
                    [0.0, 0.0],
                    [per / 4, amp],
                    [per / 2, 0.0],
                    [3 * per / 4, -amp],
                    [per, 0.0],
                ],
                "periodic": True,
            }
        else:
            exc = {
                "end": "b",
                "direction": [_round(_r(rng, -1, 1)), 0.0, _round(_r(rng, -1, 1))],
                "amplitude": _round(_log(rng, 0.001, 0.05) * chord),
                "frequency": freq,
            }
            if exc["direction"] == [0.0, 0.0, 0.0]:
                exc["direction"] = [1.0, 0.0, 0.0]
        if dyn_method in ("frequency", "auto") and rng.uniform() < 0.3:  # irregular motion
            fp = freq
            exc = {
                "end": "b",
                "direction": [1.0, 0.0, 0.0],
                "components": 16,
                "spectrum": [
                    [_round(0.5 * fp), 0.0],
                    [fp, _round((0.01 * chord) ** 2 / fp)],
                    [_round(2 * fp), 0.0],
                ],
            }
        dyn: dict[str, Any] = {
            "excitation": exc,
            "method": dyn_method,
            "elements": int(rng.choice([8, 12, 20])),
        }
        if dyn_method != "frequency":
            dyn.update(
                {
                    "points_per_period": 32,
                    "max_periods": int(rng.choice([6, 10])),
                    "ramp_periods": 1.0,
                }
            )
        analysis["dynamic"] = dyn
        meta.dynamic = dyn_method
        # the dynamic model is the discrete one: EI is fine there
    study: dict[str, Any] = {
        "name": f"stress-{seed}",
        "description": f"random stress study, seed {seed}",
        "environment": env,
        "line": line,
        "ends": ends,
        "analysis": analysis,
    }
    # a sweep of 2-3 values to get several cases per run
    if rng.uniform() < 0.6 and b_kind == "fixed":
        vals = sorted({_round(span * f) for f in (1.0, _r(rng, 0.5, 1.0), _r(rng, 1.0, 1.3))})
        study["sweep"] = {"ends.b.position.0": {"values": vals, "name": "span"}}
        meta.sweep_dim = "span"
    elif rng.uniform() < 0.4 and meta.current:
        study["sweep"] = {
            "environment.current.0.speed": {"values": [0.1, 0.5, 1.5], "name": "surface_speed"}
        }
        meta.sweep_dim = "surface_speed"
    return study, meta


def _system(rng: np.random.Generator, seed: int) -> tuple[dict, Meta]:
    depth = _log(rng, 20.0, 1500.0)
    n = int(rng.integers(2, 5))
    on_body = rng.uniform() < 0.5
    radius = depth * _log(rng, 1.5, 6.0)
    hub_z = -depth * _r(rng, 0.05, 0.4)
    points: dict[str, Any] = {}
    lines: dict[str, Any] = {}
    bodies: dict[str, Any] = {}
    if on_body:
        bodies["hull"] = {
            "kind": "prescribed",
            "position": [0.0, 0.0, _round(hub_z), 0.0, 0.0, 0.0],
        }
    else:
        points["hub"] = {
            "kind": "free",
            "position": [0.0, 0.0, _round(hub_z)],
            "mass": _round(_log(rng, 1.0, 1e4)),
        }
    for i in range(n):
        ang = 2 * math.pi * i / n + _r(rng, -0.3, 0.3)
        anchor = [_round(radius * math.cos(ang)), _round(radius * math.sin(ang)), _round(-depth)]
        points[f"anchor{i}"] = {"kind": "fixed", "position": anchor}
        if on_body:
            off = [_round(5 * math.cos(ang)), _round(5 * math.sin(ang)), 0.0]
            points[f"fair{i}"] = {"kind": "body", "body": "hull", "offset": off}
            end_b = f"fair{i}"
        else:
            end_b = "hub"
        chord = math.hypot(radius, depth + hub_z)
        length = chord * _r(rng, 1.0, 1.4)
        lines[f"leg{i}"] = {
            "a": f"anchor{i}",
            "b": end_b,
            "segments": _makeup(rng, length, WATER, False),
        }
    env: dict[str, Any] = {"fluid": "water", "depth": _round(depth)}
    current = rng.uniform() < 0.3
    if current:
        env["current"] = _current(rng, depth)
        if not on_body and rng.uniform() < 0.5:
            points["hub"]["drag_area"] = _round(_log(rng, 0.1, 5.0))
    if on_body and rng.uniform() < 0.3:  # a free body found by equilibrium
        bodies["hull"] = {
            "kind": "free",
            "position": bodies["hull"]["position"],
            "mass": _round(_log(rng, 1e3, 1e6)),
            "volume": 0.0,
        }
        bodies["hull"]["volume"] = _round(bodies["hull"]["mass"] / WATER * _r(rng, 1.0, 1.5))
    study = {
        "name": f"stress-{seed}",
        "description": f"random stress system, seed {seed}",
        "environment": env,
        "points": points,
        "bodies": bodies,
        "lines": lines,
        "analysis": {"static": {"method": "catenary", "nodes": 21}, "time_limit": 60.0},
    }
    meta = Meta(kind="system", method="catenary", rho=WATER, depth=_round(depth), current=current)
    if on_body and bodies["hull"]["kind"] == "prescribed" and rng.uniform() < 0.4:
        study["analysis"]["dynamic"] = {
            "excitation": {
                "body": "hull",
                "dof": str(rng.choice(["surge", "heave", "pitch"])),
                "amplitude": _round(_log(rng, 0.01, 0.05) * depth),
                "frequency": _round(_log(rng, 0.03, 0.3)),
            },
            "method": "time",
            "elements": 8,
            "points_per_period": 32,
            "max_periods": 6,
            "ramp_periods": 1.0,
        }
        if study["analysis"]["dynamic"]["excitation"]["dof"] == "pitch":
            study["analysis"]["dynamic"]["excitation"]["amplitude"] = 0.05
        meta.dynamic = "time"
    elif on_body and bodies["hull"]["kind"] == "prescribed":
        study["sweep"] = {
            "bodies.hull.position.0": {
                "values": [_round(-0.1 * depth), 0.0, _round(0.1 * depth)],
                "name": "surge",
            }
        }
        meta.sweep_dim = "surge"
    return study, meta
