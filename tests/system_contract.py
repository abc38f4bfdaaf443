"""The external checker of system datasets (tests/integration/test_contract_external_system.py):
what an evaluator checks from the netCDF file alone, and the small system studies it
runs. See that module's docstring."""

from __future__ import annotations

import copy
import re
from pathlib import Path

import numpy as np
import xarray as xr
import yaml

from cablestudy.cli import main

DOFS = ["surge", "sway", "heave", "roll", "pitch", "yaw"]
RHO = {"water": 1025.0, "air": 1.225, "vacuum": 0.0}


def run_study(tmp_path: Path, text: str) -> xr.Dataset:
    """``cablestudy run`` on the study text; the dataset it wrote."""
    name = yaml.safe_load(text)["name"]
    cfg = tmp_path / f"{name}.yaml"
    cfg.write_text(text)
    args = ["run", str(cfg), "--out", str(tmp_path), "--no-cache", "--no-progress"]
    assert main([*args, "--scheduler", "synchronous"]) in (0, 1)
    return xr.load_dataset(tmp_path / f"{name}.nc")


def _rotation(angles: np.ndarray) -> np.ndarray:
    """R = Rz(yaw) Ry(pitch) Rx(roll) (docs/guide/systems.md)."""
    r, p, y = angles
    cx, sx, cy, sy, cz, sz = np.cos(r), np.sin(r), np.cos(p), np.sin(p), np.cos(y), np.sin(y)
    rx = np.array([[1, 0, 0], [0, cx, -sx], [0, sx, cx]])
    ry = np.array([[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]])
    rz = np.array([[cz, -sz, 0], [sz, cz, 0], [0, 0, 1]])
    return rz @ ry @ rx


def contract_problems(ds: xr.Dataset, dynamic: bool = False) -> list[str]:
    """Where the dataset breaks the conventions and the system output contract."""
    errs = []
    for n, v in list(ds.coords.items()) + list(ds.data_vars.items()):
        if "units" not in v.attrs:
            errs.append(f"{n}: no units")
    for n in ("status", "message", "wall_time"):
        if n not in ds:
            errs.append(f"missing {n}")
    sweep = ds["status"].dims
    for n in ("line", "point", "body", "dof"):
        if n in ds.dims and (n not in ds.coords or ds[n].dtype.kind not in "UO"):
            errs.append(f"dimension {n} not labelled by names")
    if "dof" in ds.coords and list(ds["dof"].values) != DOFS:
        errs.append(f"dof labels {list(ds['dof'].values)}")
    study = yaml.safe_load(ds.attrs["study_yaml"])
    want = {
        "tension_a": ("line",),
        "tension_b": ("line",),
        "force_a": ("line", "component"),
        "force_b": ("line", "component"),
        "x": ("line", "s"),
        "y": ("line", "s"),
        "z": ("line", "s"),
        "tension": ("line", "s"),
    }
    if study.get("bodies"):
        want.update(
            body_position=("body", "dof"),
            body_force=("body", "dof"),
            body_stiffness=("body", "dof", "dof_j"),
        )
    if any(p.get("kind") == "free" for p in (study.get("points") or {}).values()):
        want["point_position"] = ("point", "component")
    if dynamic:
        want.update({f"tension_{m}_{e}": ("line",) for m in ("max", "min", "mean") for e in "ab"})
        want.update(
            tension_envelope_max=("line", "s"),
            tension_envelope_min=("line", "s"),
            dynamic_method=(),
            dynamic_method_reason=(),
        )
        if study.get("bodies"):
            want.update(body_force_max=("body", "dof"), body_force_min=("body", "dof"))
        if bool((ds["dynamic_method"] == "frequency").any()):
            want.update(tension_amplitude_a=("line",), tension_amplitude_b=("line",))
    for n, d in want.items():
        if n not in ds:
            errs.append(f"missing {n}")
        elif ds[n].dims != tuple(sweep) + d:
            errs.append(f"{n} dims {ds[n].dims} != {tuple(sweep) + d}")
    ok = ds["status"] == 0
    if dynamic and not errs:
        for e in "ab":
            mx, mn, me = (ds[f"tension_{m}_{e}"] for m in ("max", "min", "mean"))
            # the mean of a record lies between its extremes; round-off only
            if bool(((mn > me * (1 + 1e-12)) & ok).any() or ((me > mx * (1 + 1e-12)) & ok).any()):
                errs.append(f"tension_min_{e} <= tension_mean_{e} <= tension_max_{e} violated")
        big = float(ds["tension_envelope_max"].max())
        for m in ("max", "min"):  # the envelope at each end is that end's extreme
            for e, i in (("a", 0), ("b", -1)):
                env = ds[f"tension_envelope_{m}"].isel(s=i)
                if float(abs(env - ds[f"tension_{m}_{e}"]).where(ok, 0.0).max()) > 1e-9 * big:
                    errs.append(f"tension_envelope_{m} at end {e} != tension_{m}_{e}")
        if study.get("bodies"):
            # (the static force need not lie between them: the dynamic model's own
            # discrete equilibrium and the mean drag of the motion shift the mean)
            lo, hi = ds["body_force_min"], ds["body_force_max"]
            if bool(((lo > hi) & ok).any()):
                errs.append("body_force_min > body_force_max")
    for n, v in ds.data_vars.items():
        if v.dtype.kind != "f" or {"line", "s"} <= set(v.dims):
            continue  # along s, lines of different node counts are padded with NaN
        if n in ("laid_length", "tension_amplitude_a", "tension_amplitude_b"):
            continue
        if dynamic and n in _METHOD_DIAGNOSTICS:
            continue  # a diagnostic of the method that did not run
        if bool(np.isnan(v.where(ok, 0.0)).any()):
            errs.append(f"NaN in {n} at status 0")
    bad = ~ok
    if bool(bad.any()) and bool((ds["message"].where(bad, "x") == "").any()):
        errs.append("a failed case without a message")
    return errs


_METHOD_DIAGNOSTICS = (
    "dynamic_steps",
    "newton_iterations",
    "periods",
    "rejected_steps",
    "steady_converged",
    "linearisation_iterations",
)


def _case_study(base: dict, ds: xr.Dataset, case: xr.Dataset) -> dict:
    """The study text of one case: each swept value (a sweep coordinate, or a zip
    group's coordinate per path) put at the path its long_name ends with."""
    study = copy.deepcopy(base)
    sweep = set(ds["status"].dims)
    for d, coord in ds.coords.items():
        if not coord.dims or not set(coord.dims) <= sweep:
            continue
        m = re.search(r"\(([^()]*)\)\s*$", coord.attrs.get("long_name", ""))
        if m is None or coord.attrs.get("long_name", "").startswith("zipped"):
            continue
        *parents, last = m.group(1).split(".")
        node = study
        for q in parents:
            node = node[int(q)] if isinstance(node, list) else node[q]
        node[int(last) if isinstance(node, list) else last] = case[d].item()
    return study


def statics_problems(ds: xr.Dataset, balance: float = 1e-6) -> list[str]:
    """Free points balanced, each body's force the lines' pulls and moments, tension =
    |force|. ``balance``: the residual allowed, relative to the largest tension (the
    static tolerance is 1e-9 by default; 1e-6 leaves room for its scaling)."""
    errs = []
    base = yaml.safe_load(ds.attrs["study_yaml"])
    sweep = ds["status"].dims
    big = float(ds["tension_a"].max())
    for e in "ab":
        mag = np.sqrt((ds[f"force_{e}"] ** 2).sum("component"))
        if float(abs(ds[f"tension_{e}"] - mag).max()) > 1e-12 * big:
            errs.append(f"tension_{e} != |force_{e}|")
    stacked = ds.stack(case=sweep) if sweep else ds.expand_dims(case=[0])
    for k in range(stacked.sizes["case"]):
        c = stacked.isel(case=k)
        if int(c["status"]) != 0:
            continue
        study = _case_study(base, ds, c)
        env = study.get("environment", {})
        fluid = env.get("fluid", "water")
        rho = fluid["density"] if isinstance(fluid, dict) else RHO[fluid]
        g = env.get("gravity", 9.80665)
        pts, lines = study.get("points", {}), study.get("lines", {})
        pull = {p: np.zeros(3) for p in pts}
        for name, ln in lines.items():
            pull[ln["a"]] += c["force_a"].sel(line=str(name)).values
            pull[ln["b"]] += c["force_b"].sel(line=str(name)).values
        for p, spec in pts.items():
            if spec["kind"] != "free" or "current" in env:
                continue  # in a current the point's drag joins the balance
            up = (rho * spec.get("volume", 0.0) - spec.get("mass", 0.0)) * g
            net = pull[p] + np.array([0.0, 0.0, up]) + np.asarray(spec.get("force", [0, 0, 0]))
            if "point_seabed_force" in c:  # the seabed's push on a point resting on it
                net = net + c["point_seabed_force"].sel(point=p).values
            if np.abs(net).max() > balance * big:
                errs.append(f"case {k}: free point {p} out of balance by {net}")
        for name, ln in lines.items():  # each line ends at its points
            xyz = np.stack([c[k].sel(line=str(name)).values for k in "xyz"], axis=-1)
            xyz = xyz[np.all(np.isfinite(xyz), axis=1)]
            for end, at in ((ln["a"], xyz[0]), (ln["b"], xyz[-1])):
                spec = pts[end]
                if spec["kind"] == "fixed":
                    want = np.asarray(spec["position"], float)
                elif spec["kind"] == "body":  # X + R p: R = Rz Ry Rx of the body's angles
                    pos = c["body_position"].sel(body=spec["body"]).values
                    want = pos[:3] + _rotation(pos[3:]) @ np.asarray(spec["offset"], float)
                else:
                    want = c["point_position"].sel(point=end).values
                if np.abs(at - want).max() > 1e-6 * (1.0 + np.abs(want).max()):
                    errs.append(f"case {k}: line {name} ends at {at}, its point {end} at {want}")
        for b in study.get("bodies") or {}:
            rot = _rotation(c["body_position"].sel(body=b).values[3:])
            force, moment = np.zeros(3), np.zeros(3)
            for p, spec in pts.items():
                if spec["kind"] == "body" and spec["body"] == b:
                    force += pull[p]
                    moment += np.cross(rot @ np.asarray(spec["offset"], float), pull[p])
            got = c["body_force"].sel(body=b).values
            arm = max(1.0, max(np.linalg.norm(s.get("offset", 0.0)) for s in pts.values()))
            if np.abs(got[:3] - force).max() > 1e-9 * big or (
                np.abs(got[3:] - moment).max() > 1e-9 * big * arm
            ):
                errs.append(f"case {k}: body_force {got} != the lines' {force}, {moment}")
    return errs


# ------------------------------------------------------------------------- studies

LEG = (
    "{length: 320.0, diameter: 0.1, mass_per_length: 50.0, axial_stiffness: 5.0e8, "
    "drag_normal: 1.2}"
)


def spread(
    name: str, *, legs: int = 3, turn_deg: float = 0.0, analysis: str = "", sweep: str = ""
) -> str:
    """A spread of ``legs`` equal legs from anchors on the seabed (radius 300 m, depth
    100 m) to fairleads on a prescribed hull, turned by ``turn_deg`` about z."""
    points, lines = [], []
    for i in range(legs):
        a = np.deg2rad(turn_deg) + 2.0 * np.pi * i / legs
        c, s = float(np.cos(a)), float(np.sin(a))
        points.append(f"  a{i + 1}: {{kind: fixed, position: [{300 * c!r}, {300 * s!r}, -100.0]}}")
        points.append(
            f"  f{i + 1}: {{kind: body, body: hull, offset: [{10 * c!r}, {10 * s!r}, -10.0]}}"
        )
        lines.append(f"  l{i + 1}: {{a: a{i + 1}, b: f{i + 1}, segments: [{LEG}]}}")
    text = (
        f"name: {name}\nenvironment: {{fluid: water, depth: 100.0}}\npoints:\n"
        + "\n".join(points)
        + "\nbodies:\n  hull: {kind: prescribed, position: [0.0, 0.0, 0.0, 0.0, 0.0, 0.0]}"
        + "\nlines:\n"
        + "\n".join(lines)
        + "\nanalysis:\n  static: {nodes: 11}\n"
        + analysis
    )
    return text + (f"sweep:\n{sweep}" if sweep else "")


def dynamic(excitation: str, method: str = "time", more: str = "") -> str:
    """An analysis.dynamic block: few elements and steps a period, to stay fast."""
    return (
        f"  dynamic:\n    excitation: {excitation}\n    method: {method}\n    elements: 8\n"
        + ("    points_per_period: 32\n    max_periods: 12\n" if method != "frequency" else "")
        + more
    )


SURGE = "{body: hull, dof: surge, amplitude: 2.0, frequency: 0.1}"


BRIDLE = """\
name: bridle
environment: {fluid: water, depth: 200.0}
points:
  anc: {kind: fixed, position: [-400.0, 0.0, -200.0]}
  anc2: {kind: fixed, position: [400.0, 0.0, -200.0]}
  clump: {kind: free, position: [-200.0, 0.0, -150.0], mass: 4000.0, volume: 0.3,
      added_mass: 300.0, drag_area: 1.5}
  buoy: {kind: free, position: [200.0, 0.0, -100.0], mass: 500.0, volume: 4.0,
      added_mass: 4000.0, drag_area: 2.0}
  fa: {kind: body, body: ship, offset: [-8.0, 3.0, -5.0]}
  fb: {kind: body, body: ship, offset: [-8.0, -3.0, -5.0]}
  fc: {kind: body, body: ship, offset: [8.0, 0.0, -5.0]}
bodies:
  ship: {kind: prescribed, position: [0.0, 0.0, 0.0, 0.0, 0.0, 0.05]}
lines:
  leg: {a: anc, b: clump, segments: [{length: 215.0, diameter: 0.1, mass_per_length: 60.0,
      axial_stiffness: 6.0e8, drag_normal: 1.2}]}
  br1: {a: clump, b: fa, segments: [{length: 240.0, diameter: 0.08, mass_per_length: 20.0,
      axial_stiffness: 2.0e8, drag_normal: 1.2}]}
  br2: {a: clump, b: fb, segments: [{length: 240.0, diameter: 0.08, mass_per_length: 20.0,
      axial_stiffness: 2.0e8, drag_normal: 1.2}]}
  leg2: {a: anc2, b: buoy, segments: [{length: 230.0, diameter: 0.1, mass_per_length: 60.0,
      axial_stiffness: 6.0e8, drag_normal: 1.2}]}
  riser: {a: buoy, b: fc, segments: [{length: 220.0, diameter: 0.08, mass_per_length: 20.0,
      axial_stiffness: 2.0e8, drag_normal: 1.2}]}
analysis:
  static: {nodes: 11}
%s"""

TWO_BODIES = """\
name: twobody
environment: {fluid: water, depth: 150.0}
points:
  a1: {kind: fixed, position: [-400.0, 0.0, -150.0]}
  a2: {kind: fixed, position: [400.0, 0.0, -150.0]}
  a3: {kind: fixed, position: [0.0, 300.0, -150.0]}
  a4: {kind: fixed, position: [0.0, 200.0, -20.0]}
  p1: {kind: body, body: ship1, offset: [-10.0, 0.0, -5.0]}
  p1b: {kind: body, body: ship1, offset: [10.0, 0.0, -5.0]}
  p2: {kind: body, body: ship2, offset: [10.0, 0.0, -5.0]}
  p2b: {kind: body, body: ship2, offset: [-10.0, 0.0, -5.0]}
bodies:
  ship1: {kind: prescribed, position: [-100.0, 0.0, 0.0, 0.0, 0.0, 0.0]}
  ship2: {kind: prescribed, position: [100.0, 0.0, 0.0, 0.0, 0.0, 0.0]}
lines:
  m1: {a: a1, b: p1, segments: [{length: 330.0, diameter: 0.1, mass_per_length: 50.0,
      axial_stiffness: 5.0e8, drag_normal: 1.2}]}
  m2: {a: a2, b: p2, segments: [{length: 330.0, diameter: 0.1, mass_per_length: 50.0,
      axial_stiffness: 5.0e8, drag_normal: 1.2}]}
  hawser: {a: p1b, b: p2b, segments: [{length: 182.0, diameter: 0.08, mass_per_length: 8.0,
      axial_stiffness: 1.0e8, drag_normal: 1.2}]}
  span: {a: a3, b: a4, segments: [{length: 190.0, diameter: 0.05, mass_per_length: 10.0,
      axial_stiffness: 1.0e8, drag_normal: 1.2}]}
analysis:
  static: {nodes: 11}
  dynamic:
    excitation: {body: ship1, dof: surge, amplitude: 1.0, frequency: 0.1}
    method: time
    elements: 6
    points_per_period: 32
    max_periods: 8
sweep:
  analysis.dynamic.excitation.body: [ship1, ship2]
"""
