"""One-line studies nobody on the team wrote, checked from outside as an external
evaluator would: YAML text -> ``cablestudy run CONFIG --out DIR`` -> netCDF read with
xarray, against "The study file (the contract)" and "Conventions every dataset keeps"
of DESIGN.md.

:func:`conventions` is the reusable checker: every sweep key a dimension named after its
last part (``position_0`` for an index), coordinates with ``units`` and ``long_name``
(balanced, readable), a ``units`` attribute on every variable, ``status`` / ``message``
/ ``wall_time`` per case, the global attributes (study name, YAML text, its hash,
version, solver settings), ``x y z tension`` along ``s`` from end A, ``force_a`` /
``force_b`` on ``component`` with magnitude the end tension and the given end
conditions kept, ``laid_length`` matching the nodes on the seabed, and for still fluid
off the seabed the balance force_a + force_b = weight in the fluid + attachment loads
(by the study's own numbers, computed here). It runs over the studies of
``tests/contract_line_studies.py``.

The physics tests then compare with closed forms and invariances (elastic catenary,
swapped ends, a frame turned about z, quasi-static dynamics), and the bad-input tests
check that a wrong study fails before any work, naming field, value and what is allowed.
"""

from __future__ import annotations

import hashlib
import itertools
import json
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import xarray as xr
import yaml
from scipy.optimize import fsolve

import cablestudy
from cablestudy.cli import main
from tests.contract_line_studies import FORWARD, QUASI_STATIC, REVERSED, STUDIES

G = 9.80665
DENSITY = {"air": 1.225, "water": 1025.0, "vacuum": 0.0}
#: the units a swept number may carry (SI, and deg for the inputs named *_deg)
UNITS = {"1", "m", "s", "Hz", "N", "kg", "deg", "m/s", "kg/m", "N/m", "N m^2", "m^3"}
UNITS |= {"m/s^2", "kg/m^3", "N/m^2", "m^2", "rad"}


# ------------------------------------------------------------------ helpers


def run(tmp_path: Path, text: str, *extra: str) -> xr.Dataset:
    """``cablestudy run CONFIG --out DIR`` on ``text``; the dataset it wrote."""
    name = yaml.safe_load(text)["name"]
    tmp_path.mkdir(parents=True, exist_ok=True)
    cfg = tmp_path / f"{name}.yaml"
    cfg.write_text(text)
    out = tmp_path / "out"
    args = ["run", str(cfg), "--out", str(out), "--no-progress", "--scheduler", "synchronous"]
    assert main([*args, *extra]) == 0
    return xr.load_dataset(out / f"{name}.nc")


def dim_name(path: str, spec: Any) -> str:
    """The contract's dimension name: the path's last part (an index: ``<key>_<i>``),
    or the axis's own ``name``."""
    if isinstance(spec, dict) and "name" in spec:
        return str(spec["name"])
    parts = path.split(".")
    return f"{parts[-2]}_{parts[-1]}" if parts[-1].isdigit() else parts[-1]


def axis_values(spec: Any) -> list[Any]:
    if isinstance(spec, list):
        return spec
    if "values" in spec:
        return list(spec["values"])
    if "step" in spec:  # stop included
        n = int(round((spec["stop"] - spec["start"]) / spec["step"])) + 1
        return [spec["start"] + i * spec["step"] for i in range(n)]
    return list(np.linspace(spec["start"], spec["stop"], spec["num"]))


def cases(doc: dict[str, Any]) -> list[tuple[dict[str, int], dict[str, Any]]]:
    """(position on the sweep dims, the study with the swept values put in) per case."""
    sweep = doc.get("sweep") or {}
    names = [dim_name(p, s) for p, s in sweep.items()]
    values = [axis_values(s) for s in sweep.values()]
    out = []
    for combo in itertools.product(*[range(len(v)) for v in values]):
        case = json.loads(json.dumps({k: v for k, v in doc.items() if k != "sweep"}))
        for path, vals, i in zip(sweep, values, combo, strict=True):
            *head, last = path.split(".")
            node: Any = case
            for part in head:
                node = node[int(part)] if isinstance(node, list) else node[part]
            node[int(last) if isinstance(node, list) else last] = vals[i]
        out.append((dict(zip(names, combo, strict=True)), case))
    return out


def weight_and_loads(case: dict[str, Any]) -> np.ndarray:
    """Weight of the segments in the fluid plus the attachments' loads [N], from the
    study's own numbers: (m - rho A) g per length (or weight_in_fluid), an
    attachment's force, - m g and + rho V g."""
    env = case.get("environment", {})
    fluid = env.get("fluid", "water")
    rho = float(fluid["density"]) if isinstance(fluid, dict) else DENSITY[fluid]
    g = float(env.get("gravity", G))
    total = np.zeros(3)
    for seg in case["line"]["segments"]:
        area = math.pi * seg["diameter"] ** 2 / 4.0
        w = seg.get("weight_in_fluid", (seg.get("mass_per_length", 0.0) - rho * area) * g)
        total[2] -= w * seg["length"]
    for att in case["line"].get("attachments", []):
        total += np.asarray(att.get("force", [0.0, 0.0, 0.0]), dtype=float)
        total[2] += (rho * att.get("volume", 0.0) - att.get("mass", 0.0)) * g
    return total


def conventions(ds: xr.Dataset, text: str) -> list[str]:
    """Every convention of DESIGN.md a one-line dataset keeps; the faults found."""
    bad: list[str] = []
    doc = yaml.safe_load(text)
    analysis = doc.get("analysis", {})
    sweep = doc.get("sweep") or {}
    dims = [dim_name(p, s) for p, s in sweep.items()]
    for path, spec in sweep.items():
        name, values = dim_name(path, spec), axis_values(spec)
        if ds.sizes.get(name) != len(values):
            bad.append(f"sweep {path}: no dimension {name} of {len(values)}: {dict(ds.sizes)}")
        elif "labels" not in spec and all(isinstance(v, int | float) for v in values):
            if not np.allclose(ds[name].values.astype(float), values, rtol=1e-12):
                bad.append(f"{name}: coordinate {ds[name].values} for {values}")
            if ds[name].attrs.get("units") not in UNITS:
                bad.append(f"{name}: units {ds[name].attrs.get('units')!r} is not a unit")
    for name in [*ds.data_vars, *ds.coords]:
        attrs = ds[name].attrs
        if not isinstance(attrs.get("units"), str):
            bad.append(f"{name}: no units")
        long_name = str(attrs.get("long_name", ""))
        if not long_name or long_name.count("(") != long_name.count(")"):
            bad.append(f"{name}: long_name {long_name!r}")
    for name in ("status", "message", "wall_time"):
        if name not in ds or list(ds[name].dims) != dims:
            bad.append(f"{name}: not one per case on {dims}")
    if ds.attrs.get("study_name") != doc["name"] or ds.attrs.get("study_yaml") != text:
        bad.append("study name or YAML text not in the global attributes")
    if ds.attrs.get("study_sha256") != hashlib.sha256(text.encode()).hexdigest():
        bad.append("study_sha256 is not the hash of the YAML text")
    if ds.attrs.get("cablestudy_version") != cablestudy.__version__:
        bad.append("cablestudy_version")
    settings = json.loads(ds.attrs.get("solver_settings", "{}")).get("analysis", {})
    if settings.get("static", {}).get("nodes") != analysis.get("static", {}).get("nodes", 101):
        bad.append(f"solver_settings: {settings.get('static')}")
    units = {"x": "m", "y": "m", "z": "m", "tension": "N", "force_a": "N", "force_b": "N"}
    units |= {"laid_length": "m", "status": "1", "message": "1", "wall_time": "s"}
    if analysis.get("dynamic"):
        units |= {f"tension_{k}": "N" for k in ("max", "min", "mean", "static")}
    if analysis.get("modal"):
        units["natural_frequency"] = "Hz"
    for name, unit in units.items():
        if name not in ds or ds[name].attrs.get("units") != unit:
            bad.append(f"{name}: missing or not in {unit}")
    if bad:
        return bad
    if [ds[k].dims[-1] for k in ("x", "y", "z", "tension")] != ["s"] * 4:
        bad.append("x, y, z, tension not along s")
    if list(ds["component"].values) != ["x", "y", "z"] or ds["force_a"].dims[-1] != "component":
        bad.append("force_a, force_b not on component (x, y, z)")
    if analysis.get("modal") and ds["natural_frequency"].dims[-1] != "mode":
        bad.append("natural_frequency not on mode")
    for at, case in cases(doc):
        bad += [f"case {at}: {p}" for p in _case_checks(ds.isel(at), case)]
    return bad


def _case_checks(c: xr.Dataset, case: dict[str, Any]) -> list[str]:
    bad: list[str] = []
    status, message = int(c["status"]), str(c["message"].values)
    if status != 0:
        return [] if message else [f"status {status} without a message"]
    nodes = case.get("analysis", {}).get("static", {}).get("nodes", 101)
    if c.sizes["s"] > nodes:  # a swept node count: the node index, padded with NaN
        if not np.all(np.isnan(c["x"].values[nodes:])):
            bad.append(f"values past the case's {nodes} nodes")
        c = c.isel(s=slice(0, nodes))
    if message or not float(c["wall_time"]) > 0.0:
        bad.append(f"ok with message {message!r} or wall_time {float(c['wall_time'])}")
    length = sum(seg["length"] for seg in case["line"]["segments"])
    # s from end A: the coordinate, or per case where swept lengths differ (docs)
    s = c["arc_length"].values if "arc_length" in c else c["s"].values
    if len(s) != nodes or abs(s[0]) > 0.0 or abs(s[-1] - length) > 1e-12 * length:
        bad.append(f"s from {s[0]} to {s[-1]} ({len(s)} points) on a {length} m line")
    pos = np.stack([c[k].values for k in "xyz"], axis=-1)
    tension = c["tension"].values
    fa, fb = c["force_a"].values, c["force_b"].values
    # |force| is the end tension; rounding only (both come from the same solution)
    for label, force, t_end in (("a", fa, tension[0]), ("b", fb, tension[-1])):
        if not np.isclose(np.linalg.norm(force), t_end, rtol=1e-9):
            bad.append(f"|force_{label}| {np.linalg.norm(force)} is not the end tension {t_end}")
        if not np.isclose(np.linalg.norm(force), float(c[f"tension_{label}"]), rtol=1e-12):
            bad.append(f"|force_{label}| is not tension_{label}")
    for label, i, force in (("a", 0, fa), ("b", -1, fb)):
        end = case["ends"][label]
        # the solvers' tolerance is 1e-9 relative: 1e-6 of the length is far above it
        if end["kind"] == "fixed" and not np.allclose(pos[i], end["position"], atol=1e-6 * length):
            bad.append(f"end {label} at {pos[i]}, given {end['position']}")
        if end["kind"] == "force" and not np.allclose(force, -np.asarray(end["force"]), rtol=1e-9):
            bad.append(f"force_{label} {force} is not minus the applied {end['force']}")
        if end["kind"] == "mooring" and not (
            np.allclose(force[:2], -np.asarray(end["force"]), rtol=1e-9)
            and abs(pos[i][2] - end["z"]) < 1e-6 * length
        ):
            bad.append(f"mooring end {label}: force {force} at z {pos[i][2]}")
    env = case.get("environment", {})
    depth, laid = env.get("depth"), float(c["laid_length"])
    if depth is None and laid != 0.0:
        bad.append(f"laid_length {laid} without a seabed")
    if depth is not None:
        bed = env.get("seabed", {})
        rise = math.tan(math.radians(bed.get("slope_deg", 0.0)))
        heading = math.radians(bed.get("slope_heading_deg", 0.0))
        ground = -depth + rise * (pos[:, 0] * math.cos(heading) + pos[:, 1] * math.sin(heading))
        # method discrete's seabed is a spring: laid nodes sink by the weight over its
        # stiffness, 1 mm by default (keys reference); the others' seabed is rigid
        sink = 1e-6 * depth
        if case.get("analysis", {}).get("static", {}).get("method") == "discrete":
            sink = 1e-3 * (1 + 1e-6) if "stiffness" not in bed else math.inf
        if np.any(pos[:, 2] < ground - sink):
            bad.append(f"{np.max(ground - pos[:, 2])} m below the seabed")
        on = pos[:, 2] <= ground + max(sink, 1e-6 * depth)
        ds_ = np.diff(s)
        # the touchdown lies between two output points: within one spacing either way
        touching = float(np.sum(ds_[on[:-1] & on[1:]]))
        if abs(touching - laid) > ds_.max() * (1 + 1e-9):
            bad.append(f"laid_length {laid}, nodes on the seabed over {touching} m")
    if not env.get("current") and laid == 0.0:
        # still fluid, off the seabed: the supports carry the weight and the loads, to
        # the solver's tolerance (1e-9) relative to the largest tension
        loads = weight_and_loads(case)
        if not np.allclose(fa + fb, loads, rtol=0, atol=1e-7 * np.abs(tension).max()):
            bad.append(f"force_a + force_b = {fa + fb}, weight and loads {loads}")
    dyn = case.get("analysis", {}).get("dynamic")
    if dyn:
        low, mean, high, static = (
            float(c[f"tension_{k}"]) for k in ("min", "mean", "max", "static")
        )
        if not (low <= mean <= high and low <= static <= high):
            bad.append(f"tension min {low} mean {mean} max {high} static {static}")
        # the dynamic model's static end tension is the static one at the excited end, to
        # its lumped-mass discretisation (>= 14 elements: well within 1 %)
        end = dyn["excitation"]["end"]
        t_end = float(c[f"tension_{end}"])
        if not np.isclose(static, t_end, rtol=1e-2):
            bad.append(f"tension_static {static}, static tension_{end} {t_end}")
    if case.get("analysis", {}).get("modal"):
        f = c["natural_frequency"].values
        if not (np.all(f > 0.0) and np.all(np.diff(f) >= 0.0)):
            bad.append(f"natural frequencies {f}")
    return bad


# ------------------------------------------------------------------ the conventions


@pytest.mark.parametrize("key", sorted(STUDIES))
def test_study_keeps_every_convention(tmp_path: Path, key: str) -> None:
    text = STUDIES[key]
    ds = run(tmp_path, text, "--no-cache")
    assert np.all(ds["status"] == 0), ds["message"].values
    assert conventions(ds, text) == []


# ------------------------------------------------------------------ physics from outside


def _elastic_catenary(h: float, va: float, w: float, ea: float, s: np.ndarray) -> np.ndarray:
    """(x, z) from end A of an elastic catenary (Irvine 1981, eqs. 2.27-2.28 with s from
    A): horizontal tension ``h`` [N], vertical tension ``va`` [N] at A along +s, weight
    ``w`` [N/m], ``ea`` [N]."""
    v = va + w * s
    x = h * s / ea + h / w * (np.arcsinh(v / h) - np.arcsinh(va / h))
    z = (va * s + 0.5 * w * s**2) / ea + h / w * (np.hypot(1.0, v / h) - np.hypot(1.0, va / h))
    return np.stack([x, z])


@pytest.mark.parametrize("method", ["analytic", "catenary", "shooting", "discrete"])
def test_each_method_meets_the_elastic_catenary(tmp_path: Path, method: str) -> None:
    """The air study by each static method against the closed form, solved here for the
    end tensions (H, V_A) by scipy's fsolve. Analytic, catenary and shooting solve it exactly
    (to their 1e-9 tolerance, so 1e-8); the discrete lumped-mass model converges as h^2 (h = 3 m on
    120 m: about 1e-4 at 41 nodes, so 1e-3). The end tensions are those of the profile
    (tension[0], tension[-1]) and of the forces on the supports: force_a points from A
    along the line, down at the higher support (z_A = 30 m > z_B)."""
    text = STUDIES["air-analytic"].replace("method: analytic", f"method: {method}")
    ds = run(tmp_path, text.replace("name: air-analytic", f"name: air-{method}"))
    w = (5.0 - 1.225 * math.pi * 0.03**2 / 4.0) * G
    rtol = 1e-3 if method == "discrete" else 1e-8
    for i, xb in enumerate([90.0, 110.0]):
        target = np.array([xb - 10.0, 10.0 - 30.0])
        h, va = fsolve(
            lambda p, t=target: _elastic_catenary(p[0], p[1], w, 1e8, np.array([120.0]))[:, 0] - t,
            [1000.0, -300.0],
            xtol=1e-12,
        )
        c = ds.isel(position_0=i)
        assert int(c["status"]) == 0, str(c["message"].values)
        t_a, t_b = math.hypot(h, va), math.hypot(h, va + w * 120.0)
        np.testing.assert_allclose(c["force_a"], [h, 0.0, va], rtol=rtol, atol=rtol * t_a)
        np.testing.assert_allclose(c["force_b"], [-h, 0.0, -(va + w * 120.0)], rtol=rtol)
        np.testing.assert_allclose(c["tension"].values[[0, -1]], [t_a, t_b], rtol=rtol)
        assert float(c["force_a"][2]) < 0.0  # the higher support is pulled down
        shape = _elastic_catenary(h, va, w, 1e8, c["s"].values)
        np.testing.assert_allclose(c["x"] - 10.0, shape[0], atol=rtol * 120.0)
        np.testing.assert_allclose(c["z"] - 30.0, shape[1], atol=rtol * 120.0)


@pytest.mark.parametrize("method", ["catenary", "shooting", "discrete"])
def test_swapping_ends_mirrors_the_results(tmp_path: Path, method: str) -> None:
    """A two-segment line with a clump, anchored on the seabed, defined from A to B and
    from B to A: the same shape and tensions read backwards, force_a and force_b
    exchanged, the same laid length (MoorPy's invariance test; the swap changes only the
    order of the arithmetic, so the solvers' 1e-9 tolerance bounds the difference)."""
    fwd = run(tmp_path / "f", FORWARD.replace("METHOD", method))
    rev = run(tmp_path / "r", REVERSED.replace("METHOD", method))
    assert int(fwd["status"]) == int(rev["status"]) == 0
    scale = float(fwd["tension"].max())
    for k in ("x", "y", "z"):
        np.testing.assert_allclose(rev[k].values[::-1], fwd[k].values, atol=1e-8 * 180.0)
    np.testing.assert_allclose(rev["tension"].values[::-1], fwd["tension"], atol=1e-8 * scale)
    np.testing.assert_allclose(rev["force_a"], fwd["force_b"], atol=1e-8 * scale)
    np.testing.assert_allclose(rev["force_b"], fwd["force_a"], atol=1e-8 * scale)
    assert float(fwd["laid_length"]) > 0.0
    assert float(rev["laid_length"]) == pytest.approx(float(fwd["laid_length"]), abs=1e-8)


def _turned(text: str, degrees: float) -> str:
    """The study in a frame turned about z: positions, forces, the current's and the
    seabed slope's headings."""
    a = math.radians(degrees)

    def turn(v: list[float]) -> list[float]:
        return [
            math.cos(a) * v[0] - math.sin(a) * v[1],
            math.sin(a) * v[0] + math.cos(a) * v[1],
        ] + v[2:]

    doc = yaml.safe_load(text)
    doc.pop("sweep", None)
    doc["name"] += "-turned"
    env = doc["environment"]
    if "seabed" in env:
        env["seabed"]["slope_heading_deg"] = env["seabed"].get("slope_heading_deg", 0.0) + degrees
    for point in env.get("current") or []:
        point["heading_deg"] = point.get("heading_deg", 0.0) + degrees
    for att in doc["line"].get("attachments", []):
        if "force" in att:
            att["force"] = turn(att["force"])
    for end in doc["ends"].values():
        for key in ("position", "force"):
            if key in end:
                end[key] = turn(end[key])
    dynamic = doc.get("analysis", {}).get("dynamic")
    if dynamic:
        dynamic["excitation"]["direction"] = turn(dynamic["excitation"]["direction"])
    return yaml.safe_dump(doc, sort_keys=False)


@pytest.mark.parametrize(
    "key",
    [
        "segments-attachments-slope",
        "density-shooting-sheared",
        "mooring-friction",
        "frequency-range",
        "auto-period-index",
    ],
)
def test_turning_the_frame_about_z_turns_x_y_and_the_forces(tmp_path: Path, key: str) -> None:
    """Objectivity: a sloping seabed with attachments (catenary), a sheared current
    (shooting), a mooring end whose horizontal force has x and y parts, and dynamics by
    methods frequency and auto under a current, each turned by 30 degrees about z (the
    excitation's direction too): x, y and the force components turn, z, tension, the
    laid length and the dynamic tensions do not (to the solvers' 1e-9 tolerance)."""
    base = yaml.safe_load(STUDIES[key])
    base.pop("sweep")
    text = yaml.safe_dump(base, sort_keys=False)
    ref, turned = run(tmp_path / "0", text), run(tmp_path / "1", _turned(text, 30.0))
    assert int(ref["status"]) == int(turned["status"]) == 0
    c, s_ = math.cos(math.radians(30.0)), math.sin(math.radians(30.0))
    length, scale = float(ref["s"][-1]), float(ref["tension"].max())
    np.testing.assert_allclose(turned["x"], c * ref["x"] - s_ * ref["y"], atol=1e-8 * length)
    np.testing.assert_allclose(turned["y"], s_ * ref["x"] + c * ref["y"], atol=1e-8 * length)
    np.testing.assert_allclose(turned["z"], ref["z"], atol=1e-8 * length)
    np.testing.assert_allclose(turned["tension"], ref["tension"], atol=1e-8 * scale)
    for f in ("force_a", "force_b"):
        fx, fy, fz = ref[f].values
        np.testing.assert_allclose(
            turned[f], [c * fx - s_ * fy, s_ * fx + c * fy, fz], atol=1e-8 * scale
        )
    np.testing.assert_allclose(
        float(turned["laid_length"]), float(ref["laid_length"]), atol=1e-8 * length
    )
    # the dynamics too (excitation direction turned with the frame): the time domain's
    # arithmetic differs in the last bits only, its steady window as well
    for name in ("tension_max", "tension_min", "tension_mean", "tension_static"):
        if name in ref:
            np.testing.assert_allclose(turned[name], ref[name], rtol=1e-6)


def test_slow_end_motion_gives_the_static_tensions_of_the_end_positions(
    tmp_path: Path,
) -> None:
    """End B moved +-1 m along x at 0.005 Hz, 1/24 of the first natural frequency: the
    line passes through its static shapes, so tension_max and tension_min at B are the
    static end tensions with B at 91 and 89 m (a statics sweep of the same line). The
    error is the inertia and drag left, O((f / f_1)^2) = 2e-3, and the 40-element model's
    O(h^2) discretisation; 1e-2 bounds both. tension_static is the 90 m one."""
    dyn = run(tmp_path / "d", QUASI_STATIC)
    statics = QUASI_STATIC.split("  modal:")[0].replace("name: quasi-static", "name: qs-statics")
    ref = run(tmp_path / "s", statics + "sweep:\n  ends.b.position.0: [89.0, 90.0, 91.0]\n")
    assert int(dyn["status"]) == 0 and np.all(ref["status"] == 0)
    f1 = float(dyn["natural_frequency"][0])
    assert 0.005 / f1 < 0.05
    t89, t90, t91 = ref["tension_b"].values
    assert float(dyn["tension_min"]) == pytest.approx(t89, rel=1e-2)
    assert float(dyn["tension_max"]) == pytest.approx(t91, rel=1e-2)
    assert float(dyn["tension_static"]) == pytest.approx(t90, rel=1e-2)
    assert t89 < float(dyn["tension_mean"]) < t91


def test_a_case_past_max_strain_fails_and_is_kept_as_nan(tmp_path: Path) -> None:
    """max_strain on a linear law (it was silently ignored there): the 52 m span of a
    50 m line strains it by 4 % > 1 %, so that case fails with status, message and NaN
    data, its modes are not run (status 5), and the two other cases are untouched."""
    text = """\
name: max-strain
environment:
  fluid: {density: 1000.0}
line:
  segments:
    - length: 50.0
      diameter: 0.02
      mass_per_length: 1.0
      axial: {law: linear, stiffness: 1.0e6, max_strain: 0.01}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -1.0]}
  b: {kind: fixed, position: [40.0, 0.0, -1.0]}
analysis:
  static: {nodes: 11}
  modal: {modes: 2}
sweep:
  ends.b.position.0: [40.0, 52.0, 45.0]
"""
    ds = run(tmp_path, text)
    assert conventions(ds, text) == []
    np.testing.assert_array_equal(ds["position_0"], [40.0, 52.0, 45.0])  # file order kept
    bad = ds.sel(position_0=52.0)
    assert int(bad["status"]) != 0 and int(bad["modal_status"]) == 5
    assert "max_strain" in str(bad["message"].values)
    for name in ("x", "tension", "force_a", "laid_length", "natural_frequency"):
        assert np.all(np.isnan(bad[name].values)), name
        assert np.all(np.isfinite(ds[name].sel(position_0=[40.0, 45.0]).values)), name
    assert ds.attrs["cases_failed"] == 1


def test_a_second_run_reuses_every_case(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    text = STUDIES["segments-attachments-slope"]
    first = run(tmp_path, text)
    assert "4 computed, 0 reused" in capsys.readouterr().out
    second = run(tmp_path, text)
    assert "0 computed, 4 reused" in capsys.readouterr().out
    # everything but the per-case wall times and the history line (the run's own time
    # stamp, to the second: two runs a second apart differ there)
    first, second = first.drop_vars("wall_time"), second.drop_vars("wall_time")
    first.attrs.pop("history"), second.attrs.pop("history")
    xr.testing.assert_identical(first, second)


# ------------------------------------------------------------------ bad input


BASE = STUDIES["modal"]


def _edit(text: str, old: str, new: str) -> str:
    assert old in text, old
    return text.replace(old, new)


@pytest.mark.parametrize(
    ("old", "new", "expected"),
    [
        # a misspelt key
        (
            "mass_per_length: 8.0",
            "mass_per_lenght: 8.0",
            ":5: line.segments.0.mass_per_lenght: unknown key 'mass_per_lenght' (did you "
            "mean 'mass_per_length'?); allowed keys here:",
        ),
        # a wrong type
        (
            "modes: 4",
            "modes: four",
            ":11: analysis.modal.modes: must be a whole number (got 'four')",
        ),
        # a negative length
        (
            "length: 100.0",
            "length: -100.0",
            ":5: line.segments.0.length: must be greater than 0 (got -100.0)",
        ),
        # an unknown fluid
        (
            "fluid: water",
            "fluid: oil",
            ":2: environment.fluid: must be 'air', 'water' or 'vacuum', or a mapping "
            "{density: <kg/m^3>} (got 'oil')",
        ),
        # a sweep path that does not exist, by name and by index
        (
            "ends.b.position.2:",
            "ends.b.positon.2:",
            ":13: sweep.ends.b.positon.2: the path does not lead to a setting of this study: "
            "ends.b.positon does not exist (did you mean 'position'?)",
        ),
        (
            "ends.b.position.2:",
            "line.segments.3.length:",
            ":13: sweep.line.segments.3.length: the path does not lead to a setting of this "
            "study: line.segments is a list of 1 items; '3' is not an index into it "
            "(allowed 0..0)",
        ),
        # an empty sweep list, an empty range, a swept value out of range
        (
            "[-20.0, -40.0]",
            "[]",
            ":13: sweep.ends.b.position.2: an empty sweep axis gives no cases; allowed: a list "
            "of at least one value (got [])",
        ),
        (
            "ends.b.position.2: [-20.0, -40.0]",
            "line.segments.0.length: {start: 100.0, stop: 50.0, num: 0}",
            ":13: sweep.line.segments.0.length.num: must be a whole number >= 1 (got 0)",
        ),
        (
            "ends.b.position.2: [-20.0, -40.0]",
            "environment.fluid: [water, oil]",
            "environment.fluid (value from sweep.environment.fluid): must be 'air', 'water' or "
            "'vacuum', or a mapping {density: <kg/m^3>} (got 'oil')",
        ),
        # keys no analysis would use (they were silently ignored)
        (
            "fluid: water}",
            "fluid: water, seabed: {slope_deg: 5.0, friction: 0.5}}",
            ":2: environment.seabed.friction: there is no seabed without environment.depth, "
            "so no analysis uses it (got 0.5); allowed: give environment.depth, or leave the "
            "seabed key out",
        ),
        (
            "fluid: water}",
            "fluid: vacuum, current: [{z: 0.0, speed: 2.0}]}",
            ":2: environment.current: a current in a fluid of density 0 (vacuum) exerts no "
            "drag, so no analysis uses it (got [{'z': 0.0, 'speed': 2.0, 'heading_deg': 0.0}]);"
            " allowed: a fluid with density > 0",
        ),
        (
            "static: {nodes: 31}",
            "static: {nodes: 31, drag_elements: 40}",
            ":10: analysis.static.drag_elements: the study has no environment.current, so "
            "there is no drag to discretise (got 40); allowed:",
        ),
        (
            "static: {nodes: 31}",
            "static: {nodes: 31, method: shooting, drag_diameter: stretched}",
            ":10: analysis.static.drag_diameter: the diameter of the drag law, with no "
            "environment.current and no installation: there is no drag (got 'stretched'); "
            "allowed:",
        ),
        (
            "position: [0.0, 0.0, -10.0]}",
            "position: [0.0, 0.0, -10.0], bending: clamped}",
            ":7: ends.a.bending: no segment has bending_stiffness > 0, so there is no moment "
            "to hold (got 'clamped'); allowed: pinned (the default), or clamped with "
            "bending_stiffness > 0",
        ),
    ],
)
def test_bad_input_fails_before_any_work(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], old: str, new: str, expected: str
) -> None:
    """Each fault is reported at its line, naming the field, the value and what is
    allowed; the run exits 2 without a traceback and writes nothing."""
    cfg = tmp_path / "bad.yaml"
    cfg.write_text(_edit(BASE, old, new))
    out = tmp_path / "out"
    assert main(["run", str(cfg), "--out", str(out), "--no-progress"]) == 2
    err = capsys.readouterr().err
    assert (f"{cfg}{expected}" if expected.startswith(":") else expected) in err, err
    assert "Traceback" not in err
    assert not out.exists()
    assert main(["validate", str(cfg)]) == 2


def test_seabed_keys_at_their_defaults_stay_allowed_without_depth(tmp_path: Path) -> None:
    """DESIGN.md's example with ``depth`` left out (its comment: "omit: no seabed") keeps
    ``seabed: {slope_deg: 0.0, friction: 0.0}``: values that change nothing are not
    refused."""
    text = _edit(BASE, "fluid: water}", "fluid: water, seabed: {slope_deg: 0.0, friction: 0.0}}")
    ds = run(tmp_path, text)
    assert np.all(ds["status"] == 0)


def test_a_buoyant_line_between_anchors_on_the_seabed_arches_up(tmp_path: Path) -> None:
    """A riser-like buoyant line (weight_in_fluid -50 N/m) 120 m long between two
    anchors on the seabed 100 m apart rises in an inverted catenary; methods catenary
    and discrete refused it as a line 'slack on the seabed'. By symmetry each anchor
    carries half the lift, +3000 N up, whatever the gravity (the weight in the fluid is
    given); every method agrees with the analytic one (discrete: O(h^2), h = 5 m, 1e-3)."""
    text = """\
name: buoyant
environment: {fluid: water, depth: 100.0}
line:
  segments:
    - {length: 120.0, diameter: 0.2, mass_per_length: 20.0, weight_in_fluid: -50.0,
       axial_stiffness: 1.0e8}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -100.0]}
  b: {kind: fixed, position: [100.0, 0.0, -100.0]}
analysis:
  static: {nodes: 25}
sweep:
  analysis.static.method: [analytic, catenary, shooting, discrete]
  environment.gravity: [9.80665, 1.62]
"""
    ds = run(tmp_path, text)
    assert np.all(ds["status"] == 0), ds["message"].values
    assert conventions(ds, text) == []
    ref = ds.sel({"method": "analytic"})
    np.testing.assert_allclose(ds["force_a"].sel(component="z"), 3000.0, rtol=1e-9)
    np.testing.assert_allclose(ds["force_b"].sel(component="z"), 3000.0, rtol=1e-9)
    for method, rtol in (("catenary", 1e-8), ("shooting", 1e-8), ("discrete", 1e-3)):
        c = ds.sel({"method": method})
        np.testing.assert_allclose(c["force_a"], ref["force_a"], rtol=rtol, atol=1e-9)
        np.testing.assert_allclose(c["z"], ref["z"], atol=rtol * 120.0)
    assert np.all(ds["z"].values >= -100.0 - 1e-9 * 100.0) and np.all(ds["laid_length"] == 0.0)


def test_attachments_at_the_ends_load_the_supports(tmp_path: Path) -> None:
    """A 100 kg clump at s = 0 and a 300 N lift at s = L: the supports carry them with
    the line (the contract's balance), and the end tension is the end force's magnitude
    by every method (shooting reported the line's tension inside the attachment and
    failed its own verification, status 11)."""
    text = """\
name: end-attachments
environment: {fluid: water}
line:
  segments:
    - {length: 100.0, diameter: 0.03, mass_per_length: 10.0, axial_stiffness: 1.0e8}
  attachments:
    - {s: 0.0, mass: 100.0}
    - {s: 100.0, force: [0.0, 0.0, 300.0]}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -10.0]}
  b: {kind: fixed, position: [90.0, 0.0, -20.0]}
analysis:
  static: {nodes: 11}
sweep:
  analysis.static.method: [catenary, shooting, discrete]
"""
    ds = run(tmp_path, text)
    assert np.all(ds["status"] == 0), ds["message"].values
    assert conventions(ds, text) == []  # |force| = end tension, the balance with the loads
    ref = ds.sel({"method": "catenary"})
    for method, rtol in (("shooting", 1e-8), ("discrete", 1e-2)):  # discrete: h = 10 m
        np.testing.assert_allclose(ds["tension"].sel({"method": method}), ref["tension"], rtol=rtol)


def test_modes_of_a_taut_string(tmp_path: Path) -> None:
    """A nearly weightless line (gravity 1e-6) stretched 1 % between supports in vacuum
    is a taut string: f_n = n / (2 l) sqrt(T / m_l) in both transverse planes, l = 101 m
    stretched, m_l = 100/101 kg/m on it, T = EA 0.01 = 1e4 N. The modal model's 120
    lumped elements err by about (n pi / N)^2 / 12 < 3e-4 for n <= 3; 1e-3 bounds it."""
    text = """\
name: taut-string
environment: {fluid: vacuum, gravity: 1.0e-6}
line:
  segments:
    - {length: 100.0, diameter: 0.01, mass_per_length: 1.0, axial_stiffness: 1.0e6}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -10.0]}
  b: {kind: fixed, position: [101.0, 0.0, -10.0]}
analysis:
  static: {nodes: 11}
  modal: {modes: 6}
"""
    ds = run(tmp_path, text)
    assert conventions(ds, text) == []
    np.testing.assert_allclose(ds["tension"], 1e4, rtol=1e-9)
    n = np.array([1, 1, 2, 2, 3, 3])
    expected = n / (2 * 101.0) * math.sqrt(1e4 / (100.0 / 101.0))
    np.testing.assert_allclose(ds["natural_frequency"], expected, rtol=1e-3)
    assert ds["natural_frequency"].dims == ("mode",)


def test_seabed_friction_takes_mu_w_per_laid_metre_off_the_anchor(tmp_path: Path) -> None:
    """A chain held by a horizontal pull of |(60, 30)| kN at z = -10 m over an 80 m
    deep flat seabed: Coulomb friction along the laid length L_l holds mu w L_l of the
    pull, so the anchor sees H - mu w L_l (down to 0), and the suspended part, hence
    L_l, does not depend on mu. The pull keeps its direction: B lies along (2, 1)."""
    text = _edit(
        STUDIES["mooring-friction"],
        "friction: {start: 0.0, stop: 0.8, num: 3}",
        "friction: [0.0, 0.05, 0.1, 0.8]",
    )
    ds = run(tmp_path, text)
    assert np.all(ds["status"] == 0) and conventions(ds, text) == []
    w = (120.0 - 1025.0 * math.pi * 0.08**2 / 4.0) * G
    h = math.hypot(60000.0, 30000.0)
    laid = ds["laid_length"].values
    np.testing.assert_allclose(laid, laid[0], rtol=1e-9)
    expected = np.maximum(h - ds["friction"].values * w * laid, 0.0)
    np.testing.assert_allclose(ds["tension_a"], expected, rtol=1e-9, atol=1e-9 * h)
    np.testing.assert_allclose(ds["y"].isel(s=-1) / ds["x"].isel(s=-1), 0.5, rtol=1e-12)


@pytest.mark.parametrize("friction", [0.0, 0.3])
def test_discrete_mooring_end_holds_the_given_force(tmp_path: Path, friction: float) -> None:
    """Method discrete held a mooring end where the cable solution put it, so its
    horizontal force was the cable's plus the discretisation error and its own
    verification failed every such case (status 11, 'end B horizontal force off by 27
    N'). Now the end's horizontal force is the one given, to the 1e-9 tolerance, and the
    line agrees with the cable solution to the lumped model's O(h^2) (h = 5 m, 1e-3; with
    friction, the anchor to mu w h, its touchdown being at a node)."""
    text = f"""\
name: discrete-mooring
environment:
  fluid: water
  depth: 200.0
  seabed: {{friction: {friction}}}
line:
  segments:
    - {{length: 400.0, diameter: 0.1, weight_in_fluid: 1200.0, axial_stiffness: 8.0e8}}
ends:
  a: {{kind: fixed, position: [0.0, 0.0, -200.0]}}
  b: {{kind: mooring, force: [200000.0, 50000.0], z: -10.0}}
analysis:
  static: {{nodes: 81}}
sweep:
  analysis.static.method: [catenary, discrete]
"""
    ds = run(tmp_path, text)
    assert np.all(ds["status"] == 0), ds["message"].values
    assert conventions(ds, text) == []  # the force kept, B at its height
    cat, dis = ds.sel({"method": "catenary"}), ds.sel({"method": "discrete"})
    np.testing.assert_allclose(
        dis["force_b"].sel(component=["x", "y"]), [-200000.0, -50000.0], rtol=1e-9
    )
    # the anchor: friction over a laid length the discrete model ends at a node (h = 5 m)
    np.testing.assert_allclose(
        dis["force_a"], cat["force_a"], rtol=1e-3, atol=friction * 1200.0 * 5.0 + 200.0
    )
    for k in "xyz":
        np.testing.assert_allclose(dis[k].isel(s=-1), cat[k].isel(s=-1), atol=1e-3 * 400.0)
