"""Helpers and studies for tests/integration/test_contract_external_guide.py: the user
guide (README.md, docs/guide/*.md) read as a new user reads it. Its YAML blocks are taken
from the pages themselves (:func:`yaml_blocks`), so a page that changes is checked as it
stands; the studies below are a mooring engineer's first day (a chain leg, a pretension
sweep with seabed friction, a beam current, a tow line, a 3-leg spread, a vertical
hanging line, a spring), each checked against a closed form, a symmetry or MoorPy."""

from __future__ import annotations

import re
from pathlib import Path

import xarray as xr
import yaml

from cablestudy.cli import main

ROOT = Path(__file__).resolve().parents[1]
G = 9.80665
RHO_WATER = 1025.0
RHO_AIR = 1.225


def yaml_blocks(page: str) -> list[str]:
    """The ```yaml blocks of a documentation page (path relative to the repository)."""
    text = (ROOT / page).read_text()
    return re.findall(r"```yaml\n(.*?)```", text, flags=re.S)


def text_blocks(page: str) -> list[str]:
    """The plain ``` blocks (no language) of a documentation page."""
    text = (ROOT / page).read_text()
    return re.findall(r"```\n(.*?)```", text, flags=re.S)


def write(tmp_path: Path, text: str, name: str | None = None) -> Path:
    """``text`` as a study file in ``tmp_path``."""
    name = name or yaml.safe_load(text)["name"]
    tmp_path.mkdir(parents=True, exist_ok=True)
    cfg = tmp_path / f"{name}.yaml"
    cfg.write_text(text)
    return cfg


def run(tmp_path: Path, text: str, expect: int = 0) -> xr.Dataset:
    """``cablestudy run CONFIG --out DIR`` on ``text`` (exit status ``expect``); the
    dataset it wrote."""
    name = yaml.safe_load(text)["name"]
    cfg = write(tmp_path, text, name)
    out = tmp_path / "out"
    args = ["run", str(cfg), "--out", str(out), "--no-progress", "--scheduler", "synchronous"]
    assert main(args) == expect
    return xr.load_dataset(out / f"{name}.nc")


def validate(tmp_path: Path, text: str, name: str = "study") -> int:
    """``cablestudy validate CONFIG``'s exit status on ``text``."""
    return main(["validate", str(write(tmp_path, text, name))])


CHAIN = "{length: 600.0, diameter: 0.137, mass_per_length: 115.0, axial_stiffness: 4.9e8}"
#: the chain's submerged weight per length [N/m]
W_CHAIN = (115.0 - RHO_WATER * 3.141592653589793 * 0.137**2 / 4) * G

LEG = f"""\
name: leg
description: chain leg between an anchor and a fairlead, an offset sweep
environment: {{fluid: water, depth: 150.0}}
line:
  segments:
    - {CHAIN}
ends:
  a: {{kind: fixed, position: [0.0, 0.0, -150.0]}}
  b: {{kind: fixed, position: [560.0, 0.0, -15.0]}}
analysis:
  static: {{nodes: 121}}
sweep:
  ends.b.position.0: {{start: 540.0, stop: 580.0, num: 5, name: offset}}
"""

PRETENSION = f"""\
name: pretension
description: pretension sweep of a leg with a mooring end on a rough seabed
environment: {{fluid: water, depth: 150.0, seabed: {{friction: 0.5}}}}
line:
  segments:
    - {CHAIN}
ends:
  a: {{kind: fixed, position: [0.0, 0.0, -150.0]}}
  b: {{kind: mooring, force: [200000.0, 0.0], z: -15.0}}
analysis:
  static: {{nodes: 121}}
sweep:
  ends.b.force.0: [200000.0, 400000.0, 800000.0]
"""

BEAM_CURRENT = """\
name: beam-current
description: leg in a sheared beam current, the current turned over
environment:
  fluid: water
  depth: 150.0
  current:
    - {z: 0.0, speed: 1.2, heading_deg: 90.0}
    - {z: -150.0, speed: 0.3, heading_deg: 90.0}
line:
  segments:
    - {length: 600.0, diameter: 0.137, mass_per_length: 115.0, axial_stiffness: 4.9e8,
       drag_normal: 2.4, drag_tangential: 0.4}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -150.0]}
  b: {kind: fixed, position: [560.0, 0.0, -15.0]}
analysis:
  static: {nodes: 121}
sweep:
  zip:
    - name: heading
      environment.current.0.heading_deg: [90.0, 270.0]
      environment.current.1.heading_deg: [90.0, 270.0]
"""

TOW = """\
name: tow
description: tow line at 2 m/s (the water flowing past), towed body as a force end
environment:
  fluid: water
  current:
    - {z: 0.0, speed: 2.0, heading_deg: 180.0}
    - {z: -500.0, speed: 2.0, heading_deg: 180.0}
line:
  segments:
    - {length: 300.0, diameter: 0.04, mass_per_length: 6.0, axial_stiffness: 1.0e8,
       drag_normal: 1.5, drag_tangential: 0.02}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -5.0]}
  b: {kind: force, force: [-3000.0, 0.0, -8000.0]}
analysis:
  static: {nodes: 101}
sweep:
  analysis.static.method: {values: [catenary, shooting, discrete], name: solver}
"""

VERTICAL = """\
name: vertical
description: a wire hanging straight down in air with a weight at its lower end
environment: {fluid: air}
line:
  segments:
    - {length: 100.0, diameter: 0.02, mass_per_length: 3.0, axial_stiffness: 1.0e6}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 50.0]}
  b: {kind: force, force: [0.0, 0.0, -2000.0]}
analysis:
  static: {nodes: 51}
sweep:
  analysis.static.method: {values: [catenary, shooting, discrete], name: solver}
"""

SPRING = """\
name: spring
environment: {fluid: air}
line: {kind: spring, length: 10.0, axial: {law: linear, stiffness: 5000.0}}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [12.0, 0.0, -5.0]}
sweep:
  ends.b.position.0: [6.0, 12.0, 20.0]
"""

LINE_TYPES = """\
name: line-types
environment: {fluid: water, depth: 200.0}
line:
  segments:
    - length: 400.0
      line_type: {material: chain_studless, nominal_diameter: 0.076}
    - length: 800.0
      line_type: {material: polyester, nominal_diameter: 0.16}
      drag_normal: 1.4
ends:
  a: {kind: fixed, position: [0.0, 0.0, -200.0]}
  b: {kind: fixed, position: [1050.0, 0.0, -20.0]}
"""


def _leg(name: str, angle_deg: float) -> str:
    import math

    c, s = math.cos(math.radians(angle_deg)), math.sin(math.radians(angle_deg))
    return (
        f"  anchor{name}: {{kind: fixed, position: [{800 * c!r}, {800 * s!r}, -200.0]}}\n"
        f"  fair{name}: {{kind: body, body: platform, offset: [{20 * c!r}, {20 * s!r}, -14.0]}}\n"
    )


SPREAD = (
    "name: spread3\n"
    "description: three chain legs at 120 deg, the platform's surge offset curve\n"
    "environment: {fluid: water, depth: 200.0}\n"
    "points:\n" + _leg("1", 0.0) + _leg("2", 120.0) + _leg("3", 240.0) + "bodies:\n"
    "  platform: {kind: prescribed, position: [0.0, 0.0, 0.0, 0.0, 0.0, 0.0]}\n"
    "lines:\n"
    + "".join(
        f"  leg{i}: {{a: anchor{i}, b: fair{i}, segments: [{{length: 850.0, diameter: 0.137, "
        "mass_per_length: 115.0, axial_stiffness: 4.9e8}]}\n"
        for i in (1, 2, 3)
    )
    + "sweep:\n"
    "  bodies.platform.position.0: {start: -10.0, stop: 10.0, num: 11, name: surge}\n"
)

#: docs/guide/systems.md's example with its segments filled in: the clump's start makes
#: leg1 lie slack on the seabed (the solve starts from there); the sweep runs as arrays
SYSTEM_GUIDE_SLACK_START = """\
name: spread
environment: {fluid: water, depth: 100.0}
points:
  anchor1: {kind: fixed, position: [-300.0, 0.0, -100.0]}
  clump:   {kind: free, position: [-60.0, 0.0, -60.0], mass: 3000.0, volume: 0.2}
  fair1:   {kind: body, body: buoy, offset: [-5.0, 0.0, -10.0]}
bodies:
  buoy: {kind: prescribed, position: [0.0, 0.0, 0.0, 0.0, 0.0, 0.0]}
lines:
  leg1:   {a: anchor1, b: clump, segments: [{length: 280.0, diameter: 0.1,
           mass_per_length: 60.0, axial_stiffness: 5.0e8}]}
  bridle: {a: clump, b: fair1, segments: [{length: 70.0, diameter: 0.1,
           mass_per_length: 30.0, axial_stiffness: 2.0e8}]}
sweep:
  bodies.buoy.position.0: {start: -10.0, stop: 10.0, num: 3, name: surge}
"""

#: a slow surge of the leg's fairlead, by both dynamic methods in one study
SLOW_SURGE = f"""\
name: slow-surge
description: the leg's fairlead surged 2 m at 0.005 Hz, time and frequency domain
environment: {{fluid: water, depth: 150.0}}
line:
  segments:
    - {CHAIN}
ends:
  a: {{kind: fixed, position: [0.0, 0.0, -150.0]}}
  b: {{kind: fixed, position: [560.0, 0.0, -15.0]}}
analysis:
  static: {{nodes: 41}}
  dynamic:
    excitation: {{end: b, direction: [1.0, 0.0, 0.0], amplitude: 2.0, frequency: 0.005}}
    elements: 40
sweep:
  analysis.dynamic.method: [time, frequency]
"""


def law_line(law: str) -> str:
    """The ``axial:`` line of docs/guide/cable-laws.md's block for ``law``, as printed."""
    block = next(b for b in yaml_blocks("docs/guide/cable-laws.md") if "law: polynomial" in b)
    line = next(x for x in block.splitlines() if f"law: {law}" in x)
    return line.split("#")[0].strip()


def hanging_wire(axial_line: str, name: str) -> str:
    """A 100 m wire hanging straight down in air under 20 kN, with the axial law
    ``axial_line``, by the three methods that take a non-linear law."""
    return f"""\
name: {name}
environment: {{fluid: air}}
line:
  segments:
    - length: 100.0
      diameter: 0.02
      mass_per_length: 3.0
      {axial_line}
ends:
  a: {{kind: fixed, position: [0.0, 0.0, 50.0]}}
  b: {{kind: force, force: [0.0, 0.0, -20000.0]}}
analysis:
  static: {{nodes: 51}}
sweep:
  analysis.static.method: {{values: [catenary, shooting, discrete], name: solver}}
"""


#: the spread's platform surged 1 m at 0.002 Hz by both dynamic methods in one study
SPREAD_DYNAMICS = SPREAD.split("sweep:")[0].replace("name: spread3", "name: spread3-dyn") + (
    "analysis:\n"
    "  dynamic:\n"
    "    excitation: {body: platform, dof: surge, amplitude: 1.0, frequency: 0.002}\n"
    "    elements: 40\n"
    "sweep:\n"
    "  analysis.dynamic.method: [time, frequency]\n"
)
