"""Sweeps of numeric keys written from outside (from DESIGN.md and docs/, not from the
code) for tests/integration/test_contract_external_sweeps.py: issue 20's promise that
every study a user writes runs through one path, whatever it sweeps and by whichever
static method.

Each :class:`Probe` is one sweep of one numeric key on a base study, with the direction
physics says an output moves in as the key grows. :func:`check_probe` runs it through
``cablestudy run CONFIG --out DIR`` and checks the contract (the swept dimension and its
coordinate named, valued and in units as docs/guide/sweeps.md says, every output on the
sweep dims, status 0 and no message), that the output moves the right way, and that a
case of the grid equals the same case run alone, bit for bit.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr
import yaml

from cablestudy.cli import main

#: a chain-and-wire mooring leg from an anchor on the seabed (friction 0.1) to a
#: fairlead 10 m down, 350 m away: the first segment lies partly on the seabed (about
#: 270 m laid), a 2 t clump hangs in the wire 60 m before the fairlead
LEG = """\
name: NAME
environment:
  fluid: water
  depth: 100.0
  seabed: {slope_deg: 0.0, friction: 0.1}
line:
  segments:
    - {length: 200.0, diameter: 0.1, mass_per_length: 150.0, axial_stiffness: 8.0e8}
    - {length: 200.0, diameter: 0.08, mass_per_length: 60.0, axial_stiffness: 5.0e8}
  attachments:
    - {s: 330.0, mass: 2000.0}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -100.0]}
  b: {kind: fixed, position: [350.0, 0.0, -10.0]}
analysis:
  static: {method: METHOD, nodes: 21}
"""

#: a uniform wire hanging free in water between supports 20 m apart in height, 119 m
#: apart horizontally for a 130 m length: no seabed, no attachment, no current, so every
#: static method (analytic too) takes it
SPAN = """\
name: NAME
environment: {fluid: water}
line:
  segments:
    - {length: 130.0, diameter: 0.03, mass_per_length: 5.0, axial_stiffness: 4.0e7}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -30.0]}
  b: {kind: fixed, position: [119.0, 0.0, -10.0]}
analysis:
  static: {method: METHOD, nodes: 21}
"""

#: SPAN with a 300 kg clump at mid-length and a {density} fluid (to sweep it)
SPAN_CLUMP = """\
name: NAME
environment: {fluid: {density: 1025.0}}
line:
  segments:
    - {length: 130.0, diameter: 0.03, mass_per_length: 5.0, axial_stiffness: 4.0e7}
  attachments:
    - {s: 65.0, mass: 300.0, force: [0.0, 0.0, 0.0]}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -30.0]}
  b: {kind: fixed, position: [119.0, 0.0, -10.0]}
analysis:
  static: {method: METHOD, nodes: 21}
"""

#: SPAN in a uniform current flowing to +y (heading 90 deg): the drag pushes the line
#: out of the x-z plane of its ends
CURRENT = """\
name: NAME
environment:
  fluid: water
  current:
    - {z: 0.0, speed: 0.5, heading_deg: 90.0}
    - {z: -100.0, speed: 0.5, heading_deg: 90.0}
line:
  segments:
    - {length: 130.0, diameter: 0.03, mass_per_length: 5.0, axial_stiffness: 4.0e7}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -30.0]}
  b: {kind: fixed, position: [119.0, 0.0, -10.0]}
analysis:
  static: {method: METHOD, nodes: 21}
"""

#: a cable towed from a fixed point A by a known force at B (a `force` end)
TOW = """\
name: NAME
environment: {fluid: water}
line:
  segments:
    - {length: 100.0, diameter: 0.03, mass_per_length: 5.0, axial_stiffness: 4.0e7}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -5.0]}
  b: {kind: force, force: [-2000.0, 0.0, -500.0]}
analysis:
  static: {method: METHOD, nodes: 21}
"""

#: a mooring leg whose fairlead B is a `mooring` end: known horizontal force and height
MOOR = """\
name: NAME
environment:
  fluid: water
  depth: 80.0
  seabed: {friction: 0.1}
line:
  segments:
    - {length: 300.0, diameter: 0.08, mass_per_length: 120.0, axial_stiffness: 5.0e8}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -80.0]}
  b: {kind: mooring, force: [60000.0, 0.0], z: -10.0}
analysis:
  static: {method: METHOD, nodes: 21}
"""

#: SPAN with its stiffness as an axial law: linear (the kernels take it as EA) and a
#: polynomial T = A e + B e^2 (the general solver's), and SPAN made of a line type
SPAN_LINEAR = SPAN.replace("axial_stiffness: 4.0e7}", "axial: {law: linear, stiffness: 4.0e7}}")
SPAN_POLY = SPAN.replace(
    "axial_stiffness: 4.0e7}", "axial: {law: polynomial, coefficients: [4.0e7, 1.0e8]}}"
)
SPAN_TYPE = SPAN.replace(
    "diameter: 0.03, mass_per_length: 5.0, axial_stiffness: 4.0e7}",
    "line_type: {material: wire_six_strand, nominal_diameter: 0.03}}",
)

BASES = {"leg": LEG, "span": SPAN, "span_clump": SPAN_CLUMP, "current": CURRENT}
BASES |= {"span_linear": SPAN_LINEAR, "span_poly": SPAN_POLY, "span_type": SPAN_TYPE}
BASES |= {"tow": TOW, "moor": MOOR}
#: CURRENT over a seabed it does not reach: the compiled drag iteration takes lines
#: without a seabed only, so its current cases go to the general solver
BASES |= {
    "current_seabed": CURRENT.replace("  fluid: water\n", "  fluid: water\n  depth: 150.0\n", 1)
}


def _mid(ds: xr.Dataset, var: str) -> np.ndarray:
    """``var`` at the middle output point along the line, per case."""
    return ds[var].isel(s=ds.sizes["s"] // 2).values


def _comp(var: str, k: int) -> Callable[[xr.Dataset], np.ndarray]:
    return lambda ds: ds[var].isel(component=k).values


def _scalar(var: str) -> Callable[[xr.Dataset], np.ndarray]:
    return lambda ds: ds[var].values


@dataclass(frozen=True)
class Probe:
    """One swept numeric key on a base study: the output that physics says moves, and
    which way (+1 up, -1 down) as the key's value grows."""

    base: str
    path: str
    values: tuple[float, ...]
    output: str  # a readable name of what is measured
    measure: Callable[[xr.Dataset], np.ndarray]
    direction: int
    units: str
    methods: tuple[str, ...]
    why: str

    @property
    def id(self) -> str:
        return f"{self.base}:{self.path}"


CAT_SHOOT_DISC = ("catenary", "shooting", "discrete")
ALL = ("catenary", "shooting", "analytic", "discrete")

PROBES: tuple[Probe, ...] = (
    Probe(
        "leg",
        "line.segments.0.length",
        (190.0, 200.0, 210.0),
        "tension_b",
        _scalar("tension_b"),
        -1,
        "m",
        CAT_SHOOT_DISC,
        "a longer leg lays more chain and hangs with less tension at the fairlead",
    ),
    Probe(
        "leg",
        "line.segments.0.mass_per_length",
        (130.0, 150.0, 170.0),
        "tension_b",
        _scalar("tension_b"),
        +1,
        "kg/m",
        CAT_SHOOT_DISC,
        "a heavier chain is a heavier catenary",
    ),
    Probe(
        "leg",
        "line.segments.1.diameter",
        (0.06, 0.08, 0.10),
        "tension_b",
        _scalar("tension_b"),
        -1,
        "m",
        CAT_SHOOT_DISC,
        "a thicker wire of the same mass displaces more water: lighter in water",
    ),
    Probe(
        "leg",
        "environment.seabed.friction",
        (0.0, 0.02, 0.04),
        "tension_a",
        _scalar("tension_a"),
        -1,
        "1",
        CAT_SHOOT_DISC,
        "friction on the laid chain takes mu w per laid metre off the anchor",
    ),
    Probe(
        "leg",
        "environment.depth",
        (100.0, 102.0, 104.0),
        "laid_length",
        _scalar("laid_length"),
        -1,
        "m",
        ("catenary",),
        "a seabed farther below the same ends holds less of the line",
    ),
    Probe(
        "leg",
        "environment.depth",
        (100.0, 102.0, 104.0),
        "tension_b",
        _scalar("tension_b"),
        +1,
        "m",
        ("catenary", "discrete"),
        "the seabed lowered under the same ends: more chain hangs from the fairlead",
    ),
    Probe(
        "leg",
        "environment.gravity",
        (9.7, 9.80665, 9.9),
        "tension_b",
        _scalar("tension_b"),
        +1,
        "m/s^2",
        CAT_SHOOT_DISC,
        "more gravity, more weight in water (weight and buoyancy scale alike)",
    ),
    Probe(
        "leg",
        "line.attachments.0.mass",
        (1000.0, 2000.0, 3000.0),
        "tension_b",
        _scalar("tension_b"),
        +1,
        "kg",
        CAT_SHOOT_DISC,
        "a heavier clump is more weight to hold",
    ),
    Probe(
        "leg",
        "ends.b.position.0",
        (340.0, 350.0, 360.0),
        "tension_b",
        _scalar("tension_b"),
        +1,
        "m",
        CAT_SHOOT_DISC,
        "a fairlead farther from the anchor lifts more chain",
    ),
    Probe(
        "leg",
        "ends.a.position.0",
        (-10.0, 0.0, 10.0),
        "tension_b",
        _scalar("tension_b"),
        -1,
        "m",
        ("catenary",),
        "an anchor nearer the fairlead slackens the leg",
    ),
    Probe(
        "span",
        "line.segments.0.axial_stiffness",
        (2.0e7, 4.0e7, 8.0e7),
        "tension_b",
        _scalar("tension_b"),
        +1,
        "N",
        ALL,
        "a stiffer wire stretches less between the same supports: less sag, more tension",
    ),
    Probe(
        "span",
        "line.segments.0.weight_in_fluid",
        (30.0, 40.0, 50.0),
        "tension_b",
        _scalar("tension_b"),
        +1,
        "N/m",
        ALL,
        "the weight in water, given, overrides mass minus buoyancy in statics",
    ),
    Probe(
        "span",
        "ends.b.position.2",
        (-12.0, -10.0, -8.0),
        "tension_b",
        _scalar("tension_b"),
        +1,
        "m",
        ALL,
        "a higher support stretches the span taut",
    ),
    Probe(
        "span_linear",
        "line.segments.0.axial.stiffness",
        (2.0e7, 4.0e7, 8.0e7),
        "tension_b",
        _scalar("tension_b"),
        +1,
        "N",
        ALL,
        "the linear law's stiffness is EA: stiffer, less sag, more tension",
    ),
    Probe(
        "span_poly",
        "line.segments.0.axial.coefficients.0",
        (2.0e7, 4.0e7, 8.0e7),
        "tension_b",
        _scalar("tension_b"),
        +1,
        "N",
        CAT_SHOOT_DISC,
        "the polynomial law's linear term: stiffer, less sag, more tension",
    ),
    Probe(
        "span_type",
        "line.segments.0.line_type.nominal_diameter",
        (0.02, 0.03, 0.04),
        "tension_b",
        _scalar("tension_b"),
        +1,
        "m",
        ALL,
        "a thicker wire rope of the library weighs more per metre",
    ),
    Probe(
        "span_clump",
        "environment.fluid.density",
        (0.0, 1025.0, 2000.0),
        "tension_b",
        _scalar("tension_b"),
        -1,
        "kg/m^3",
        CAT_SHOOT_DISC,
        "a denser fluid buoys the wire up",
    ),
    Probe(
        "span_clump",
        "line.attachments.0.volume",
        (0.0, 0.1, 0.2),
        "tension_b",
        _scalar("tension_b"),
        -1,
        "m^3",
        CAT_SHOOT_DISC,
        "the clump's displaced volume buoys it",
    ),
    Probe(
        "span_clump",
        "line.attachments.0.force.2",
        (-2000.0, 0.0, 2000.0),
        "tension_b",
        _scalar("tension_b"),
        -1,
        "N",
        CAT_SHOOT_DISC,
        "an upward point force carries some of the weight",
    ),
    Probe(
        "span_clump",
        "line.attachments.0.s",
        (40.0, 65.0, 90.0),
        "-force_a.z",
        lambda ds: -ds["force_a"].isel(component=2).values,
        -1,
        "m",
        CAT_SHOOT_DISC,
        "a clump farther from A puts less of its weight on A",
    ),
    Probe(
        "current",
        "environment.current.0.speed",
        (0.25, 0.5, 1.0),
        "y at mid-length",
        lambda ds: _mid(ds, "y"),
        +1,
        "m/s",
        CAT_SHOOT_DISC,
        "faster current, more drag, the line blown farther to +y",
    ),
    Probe(
        "current",
        "environment.current.1.heading_deg",
        (60.0, 90.0, 120.0),
        "x at mid-length",
        lambda ds: _mid(ds, "x"),
        -1,
        "deg",
        CAT_SHOOT_DISC,
        "turning the deep current from +x towards -x turns its drag on the line with it",
    ),
    Probe(
        "current",
        "line.segments.0.drag_normal",
        (0.6, 1.2, 2.4),
        "y at mid-length",
        lambda ds: _mid(ds, "y"),
        +1,
        "1",
        CAT_SHOOT_DISC,
        "more drag coefficient, more drag",
    ),
    Probe(
        "tow",
        "ends.b.force.0",
        (-3000.0, -2000.0, -1000.0),
        "x of end B",
        lambda ds: ds["x"].isel(s=-1).values,
        +1,
        "N",
        CAT_SHOOT_DISC,
        "the tow pulls B to -x: less pull, B hangs nearer below A",
    ),
    Probe(
        "moor",
        "ends.b.force.0",
        (40000.0, 60000.0, 80000.0),
        "x of end B",
        lambda ds: ds["x"].isel(s=-1).values,
        +1,
        "N",
        CAT_SHOOT_DISC,
        "more horizontal pull at the fairlead lifts more chain off the seabed",
    ),
    Probe(
        "moor",
        "ends.b.z",
        (-20.0, -10.0, 0.0),
        "tension_b",
        _scalar("tension_b"),
        +1,
        "m",
        CAT_SHOOT_DISC,
        "a higher fairlead at the same horizontal pull hangs more chain",
    ),
)


def study_text(base: str, method: str | None, name: str) -> str:
    """The base study's text, named ``name``, with ``method`` (None: the key left out,
    the default catenary)."""
    text = BASES[base].replace("NAME", name)
    if method is None:
        return text.replace("static: {method: METHOD, nodes: 21}", "static: {nodes: 21}")
    return text.replace("METHOD", method)


def with_sweep(text: str, sweep: dict[str, Any]) -> str:
    """``text`` with a ``sweep:`` block appended, as a user would write it."""
    return text + yaml.safe_dump({"sweep": sweep}, default_flow_style=None, sort_keys=False)


def set_path(text: str, path: str, value: Any) -> str:
    """``text`` with the key at dotted ``path`` set to ``value`` (one case written out)."""
    data = yaml.safe_load(text)
    node = data
    parts = path.split(".")
    for part in parts[:-1]:
        node = node[int(part)] if isinstance(node, list) else node[part]
    last = parts[-1]
    if isinstance(node, list):
        node[int(last)] = value
    else:
        node[last] = value
    return yaml.safe_dump(data, sort_keys=False)


def run(folder: Path, text: str, *extra: str) -> tuple[int, xr.Dataset | None]:
    """``cablestudy run CONFIG --out DIR`` on ``text``: its exit code and the dataset."""
    name = yaml.safe_load(text)["name"]
    folder.mkdir(parents=True, exist_ok=True)
    cfg = folder / f"{name}.yaml"
    cfg.write_text(text)
    out = folder / "out"
    args = ["run", str(cfg), "--out", str(out), "--no-progress", "--scheduler", "synchronous"]
    code = main([*args, "--no-cache", *extra])
    path = out / f"{name}.nc"
    return code, (xr.load_dataset(path) if code == 0 and path.exists() else None)


#: per-case variables that are not results (the time a case took)
NOT_RESULTS = {"wall_time"}


#: names a swept key's last part shares with an output's dimension or variable
#: (docs/guide/sweeps.md: such a dimension is prefixed with its parent key)
OUTPUT_NAMES = {"s", "z", "tension"}


def dim_of(path: str) -> str:
    """The dimension docs/guide/sweeps.md names a swept path after: its last part, an
    index part giving ``<parent>_<index>``."""
    parts = path.split(".")
    named = [p for p in parts[:-1] if not p.isdigit()]
    if parts[-1].isdigit() or parts[-1] in OUTPUT_NAMES:
        return f"{named[-1]}_{parts[-1]}"
    return parts[-1]


def contract_faults(ds: xr.Dataset, probe: Probe) -> list[str]:
    """What the dataset of ``probe``'s sweep breaks of the contract."""
    faults: list[str] = []
    dim = dim_of(probe.path)
    if dim not in ds.dims:
        return [f"no dimension {dim!r} (dims {dict(ds.sizes)})"]
    coord = ds[dim]
    if not np.array_equal(coord.values, np.array(probe.values)):
        faults.append(f"{dim} coordinate {coord.values} != swept {probe.values}")
    if coord.attrs.get("units") != probe.units:
        faults.append(f"{dim} units {coord.attrs.get('units')!r}, expected {probe.units!r}")
    if probe.path not in str(coord.attrs.get("long_name", "")):
        faults.append(f"{dim} long_name {coord.attrs.get('long_name')!r} does not name the path")
    for name, var in ds.data_vars.items():
        if dim not in var.dims:
            faults.append(f"{name} is not on the swept dimension ({var.dims})")
        if "units" not in var.attrs:
            faults.append(f"{name} has no units")
    for name in ("x", "y", "z", "tension"):
        if ds[name].dims != (dim, "s"):
            faults.append(f"{name} dims {ds[name].dims} != {(dim, 's')}")
    for name in ("force_a", "force_b"):
        if ds[name].dims != (dim, "component"):
            faults.append(f"{name} dims {ds[name].dims} != {(dim, 'component')}")
    bad = ds["status"].values != 0
    if bad.any():
        faults.append(f"status {ds['status'].values}, messages {ds['message'].values[bad]}")
    if any(str(m) for m in ds["message"].values):
        faults.append(f"messages on cases: {ds['message'].values}")
    return faults


def direction_faults(ds: xr.Dataset, probe: Probe) -> list[str]:
    """Whether the measured output moves strictly in ``probe.direction`` along the sweep."""
    got = np.asarray(probe.measure(ds), dtype=float)
    step = np.diff(got) * probe.direction
    if not (np.all(np.isfinite(got)) and np.all(step > 0.0)):
        return [f"{probe.output} along {probe.path}={probe.values}: {got} ({probe.why})"]
    return []


def alone_faults(grid: xr.Dataset, alone: xr.Dataset, dim: str, k: int) -> list[str]:
    """Every result variable of case ``k`` of the grid against the case run alone,
    bit for bit (NaN equal to NaN; text equal)."""
    faults: list[str] = []
    case = grid.isel({dim: k})
    if "arc_length" in case:
        # cases of other arc lengths: s is the node index, arc_length the case's own
        # (docs/guide/results.md); the case alone has its arc lengths as the s coordinate;
        # a case of fewer nodes than the grid's most is NaN past its own
        n = alone.sizes["s"]
        arc = case["arc_length"].values
        if not (np.array_equal(arc[:n], alone["s"].values) and np.all(np.isnan(arc[n:]))):
            faults.append("arc_length of the grid case != s of the case alone")
        for name in [v for v in case.data_vars if "s" in case[v].dims]:
            rest = case[name].isel(s=slice(n, None)).values
            if rest.size and not np.all(np.isnan(rest)):
                faults.append(f"{name}: values past the case's {n} nodes")
        case = case.drop_vars("arc_length").isel(s=slice(0, n))
    for name in sorted(set(case.data_vars) - NOT_RESULTS):
        if name not in alone:
            faults.append(f"{name} in the grid, not in the case run alone")
            continue
        a, b = case[name].values, alone[name].values
        same = a.shape == b.shape and (
            np.array_equal(a, b, equal_nan=a.dtype.kind == "f")
            if a.dtype.kind in "fiu"
            else (a == b).all()
        )
        if not same:
            diff = np.nanmax(np.abs(a - b)) if a.dtype.kind == "f" and a.shape == b.shape else ""
            faults.append(f"{name}: grid case {k} != alone {diff}")
    for name in sorted(set(alone.data_vars) - set(case.data_vars) - NOT_RESULTS):
        faults.append(f"{name} in the case run alone, not in the grid")
    return faults


def check_probe(folder: Path, probe: Probe, method: str | None, k: int = 1) -> list[str]:
    """Every fault of ``probe`` by ``method``: the contract, the direction, and case
    ``k`` of the grid against the same case run alone."""
    tag = f"{probe.base}-{method or 'default'}-{dim_of(probe.path)}"
    base = study_text(probe.base, method, tag)
    code, ds = run(folder / "grid", with_sweep(base, {probe.path: list(probe.values)}))
    if ds is None:
        return [f"{tag}: the sweep did not run (exit {code})"]
    faults = contract_faults(ds, probe) + direction_faults(ds, probe)
    one = set_path(base, probe.path, probe.values[k])
    code, alone = run(folder / "alone", one)
    if alone is None:
        return [*faults, f"{tag}: case {k} alone did not run (exit {code})"]
    faults += alone_faults(ds, alone, dim_of(probe.path), k)
    return [f"{tag}: {f}" for f in faults]


__all__ = [
    "PROBES",
    "Probe",
    "alone_faults",
    "check_probe",
    "contract_faults",
    "dim_of",
    "direction_faults",
    "run",
    "set_path",
    "study_text",
    "with_sweep",
]
