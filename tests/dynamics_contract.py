"""One-line dynamic studies written from outside, from DESIGN.md and the user guide
(docs/guide/line-model.md, docs/frequency-domain.md, docs/reference/keys.md), not from
the code or configs/, for tests/integration/test_contract_external_dynamics.py. Each is a
YAML text as an OrcaFlex or MoorPy user would write it, small enough to run in a fraction
of a second once the kernels are compiled.

Together they cover ``analysis.dynamic`` by methods ``time``, ``frequency`` and ``auto``:
harmonic end motion off the axes, at end A or B, at both ends, with a phase; a periodic
time table; a displacement spectrum; a current (still, in plane, across the plane) with
Morison drag; a laid line on the seabed; bending with pinned and clamped ends and a
lumped body (mass, volume, added mass, drag area); histories of points and of the whole
line; ``transfer_function``; sweeps of frequency, amplitude, direction (labelled), end,
elements, time steps and duration; modal analysis of a string in water; a massless
spring line; the quasi-static database. :func:`mirrored` and :func:`turned` build the
same study with ends A and B swapped or the frame turned about z.
"""

from __future__ import annotations

import math
from typing import Any

import yaml

#: a 20.2 m wire between supports 20 m apart and 1 m apart in height, in air (no drag
#: worth the name): the frequency and time domain see the same linear line
AIR = """\
name: {name}
environment: {{fluid: air}}
line:
  segments:
    - {{length: 20.2, diameter: 0.01, mass_per_length: 1.0, axial_stiffness: 2.0e6}}
ends:
  a: {{kind: fixed, position: [0.0, 0.0, 0.0]}}
  b: {{kind: fixed, position: [20.0, 0.0, -1.0]}}
analysis:
  static: {{nodes: 41}}
  dynamic:
    method: {method}
    excitation: {excitation}
{extra}"""

#: end B moved along a direction off the axes, normalised by cablestudy
OFF_AXIS = "{end: b, direction: [1.0, 0.0, 0.5], amplitude: 0.002, frequency: 0.3}"

#: a taut 46 m line in water with transverse structural damping (linear, so both methods
#: damp the transients alike) and Morison drag switched off or on
WATER = """\
name: {name}
environment:
  fluid: water
  current:
    - {{z: 0.0, speed: {speed}, heading_deg: {heading}}}
    - {{z: -50.0, speed: {speed}, heading_deg: {heading}}}
line:
  segments:
    - {{length: 46.0, diameter: 0.03, mass_per_length: 4.0, axial_stiffness: 1.0e7,
        drag_normal: {cd}, drag_tangential: 0.0, damping_transverse: {damping}}}
ends:
  a: {{kind: fixed, position: [0.0, 0.0, -30.0]}}
  b: {{kind: fixed, position: [38.0, 0.0, -10.0]}}
analysis:
  static: {{nodes: 41}}
  dynamic:
    method: {method}
    excitation: {excitation}
{extra}"""

#: a chain-like line anchored on a 50 m deep seabed, fairlead at B 5 m below the surface
LAID = """\
name: {name}
environment:
  fluid: water
  depth: 50.0
line:
  segments:
    - {{length: 150.0, diameter: 0.05, mass_per_length: 40.0, axial_stiffness: 2.0e8,
        damping_transverse: 50.0}}
ends:
  a: {{kind: fixed, position: [0.0, 0.0, -50.0]}}
  b: {{kind: fixed, position: [120.0, 0.0, -5.0]}}
analysis:
  static: {{nodes: 61}}
{dynamic}{extra}"""

#: a line with bending stiffness and a lumped body, static method discrete
BENT = """\
name: {name}
environment: {{fluid: water}}
line:
  segments:
    - {{length: 46.0, diameter: 0.03, mass_per_length: 4.0, axial_stiffness: 1.0e7,
        bending_stiffness: 500.0, damping_transverse: 20.0}}
  attachments:
    - {{s: 20.0, mass: 50.0, volume: 0.01, added_mass: 20.0, drag_area: 0.05}}
ends:
  a: {{kind: fixed, position: [0.0, 0.0, -30.0], bending: {bending}}}
  b: {{kind: fixed, position: [38.0, 0.0, -10.0], bending: {bending}}}
analysis:
  static: {{method: discrete, nodes: 81}}
  dynamic:
    method: {method}
    excitation: {excitation}
sweep:
  analysis.dynamic.excitation.frequency: [0.05, 0.3]
"""


#: the laid line's fairlead surged 5 cm at 0.05 Hz by the method given (``% method``)
LAID_SURGE = (
    "  dynamic:\n    method: %s\n    elements: 60\n"
    "    excitation: {end: b, direction: [1.0, 0.0, 0.0], amplitude: 0.05, frequency: 0.05}\n"
)


def air(name: str, method: str, excitation: str = OFF_AXIS, extra: str = "") -> str:
    return AIR.format(name=name, method=method, excitation=excitation, extra=extra)


def water(
    name: str,
    method: str,
    *,
    speed: float = 0.0,
    heading: float = 0.0,
    cd: float = 1.2,
    damping: float = 20.0,
    excitation: str = "{end: b, direction: [1.0, 0.0, 0.0], amplitude: 0.002, frequency: 0.2}",
    extra: str = "",
) -> str:
    return WATER.format(
        name=name,
        method=method,
        speed=speed,
        heading=heading,
        cd=cd,
        damping=damping,
        excitation=excitation,
        extra=extra,
    )


def laid(name: str, dynamic: str = "", extra: str = "") -> str:
    return LAID.format(name=name, dynamic=dynamic, extra=extra)


def bent(name: str, method: str, bending: str, excitation: str) -> str:
    return BENT.format(name=name, method=method, bending=bending, excitation=excitation)


def _periodic_sine_table(amplitude: float, frequency: float, samples: int) -> str:
    """A sine of one period as a periodic table of ``samples`` intervals."""
    period = 1.0 / frequency
    rows = [
        [period * k / samples, amplitude * math.sin(2 * math.pi * k / samples)]
        for k in range(samples)
    ]
    rows.append([period, 0.0])
    return ", ".join(f"[{t!r}, {u!r}]" for t, u in rows)


#: the studies the convention checker runs over (each also used by a physics test)
STUDIES: dict[str, str] = {
    "air-time": air("air-time", "time"),
    "air-frequency": air("air-frequency", "frequency"),
    "air-auto-transfer": air(
        "air-auto-transfer",
        "auto",
        extra="    transfer_function: {start: 0.1, stop: 0.5, num: 5}\n",
    ),
    "air-both-ends": air(
        "air-both-ends",
        "time",
        excitation=(
            "\n      - {end: a, direction: [-1.0, 0.0, 0.0], amplitude: 0.002, frequency: 0.3}"
            "\n      - {end: b, direction: [1.0, 0.0, 0.0], amplitude: 0.002, frequency: 0.3}"
        ),
    ),
    "air-table": air(
        "air-table",
        "time",
        excitation="{end: b, direction: [1.0, 0.0, 0.5], periodic: true, table: ["
        + _periodic_sine_table(0.002, 0.3, 64)
        + "]}",
    ),
    "air-history": air(
        "air-history",
        "time",
        extra=(
            "    history: {points: [0.0, 10.1, 20.2], periods: 1, samples_per_period: 16,"
            " whole_line: true}\n"
        ),
    ),
    "air-direction-end": air(
        "air-direction-end",
        "frequency",
        extra=(
            "sweep:\n"
            "  analysis.dynamic.excitation.direction: {values: [[1, 0, 0], [0, 1, 0],"
            " [0, 0, 1]], labels: [surge, sway, heave], name: motion}\n"
            "  analysis.dynamic.excitation.end: [a, b]\n"
        ),
    ),
    "air-elements-steps": air(
        "air-elements-steps",
        "time",
        extra=(
            "sweep:\n  analysis.dynamic.elements: [20, 40, 80]\n"
            "  analysis.dynamic.points_per_period: [32, 64]\n"
        ),
    ),
    "air-duration": air(
        "air-duration",
        "time",
        extra=(
            "    history: {points: [20.2], periods: 1, samples_per_period: 8}\n"
            "sweep:\n  analysis.dynamic.duration: [10.0, 20.0]\n"
        ),
    ),
    "water-damped-time": water(
        "water-damped-time",
        "time",
        cd=0.0,
        extra="sweep:\n  analysis.dynamic.excitation.frequency: [0.1, 0.2, 0.3]\n",
    ),
    "water-damped-frequency": water(
        "water-damped-frequency",
        "frequency",
        cd=0.0,
        extra="sweep:\n  analysis.dynamic.excitation.frequency: [0.1, 0.2, 0.3]\n",
    ),
    "water-cross-current-time": water(
        "water-cross-current-time",
        "time",
        speed=0.5,
        heading=90.0,
        damping=0.0,
        extra="sweep:\n  analysis.dynamic.excitation.amplitude: [0.002, 0.01]\n",
    ),
    "water-cross-current-frequency": water(
        "water-cross-current-frequency",
        "frequency",
        speed=0.5,
        heading=90.0,
        damping=0.0,
        extra="sweep:\n  analysis.dynamic.excitation.amplitude: [0.002, 0.01]\n",
    ),
    "water-spectrum-time": water(
        "water-spectrum-time",
        "time",
        cd=0.0,
        excitation=(
            "{end: b, direction: [1.0, 0.0, 0.0], components: 32,"
            " spectrum: [[0.05, 0.0], [0.1, 1.0e-4], [0.2, 1.0e-4], [0.25, 0.0]]}"
        ),
        extra="    history: {periods: 1, samples_per_period: 1024}\n",
    ),
    "water-spectrum-frequency": water(
        "water-spectrum-frequency",
        "frequency",
        cd=0.0,
        excitation=(
            "{end: b, direction: [1.0, 0.0, 0.0], components: 32,"
            " spectrum: [[0.05, 0.0], [0.1, 1.0e-4], [0.2, 1.0e-4], [0.25, 0.0]]}"
        ),
    ),
    "laid-slow-frequency": laid(
        "laid-slow-frequency",
        "  dynamic:\n    method: frequency\n    elements: 60\n"
        "    excitation: {end: b, direction: [1.0, 0.0, 0.0], amplitude: 0.05,"
        " frequency: 0.002}\n",
    ),
    "laid-slow-time": laid(
        "laid-slow-time",
        "  dynamic:\n    method: time\n    elements: 120\n"
        "    excitation: {end: b, direction: [1.0, 0.0, 0.0], amplitude: 1.0,"
        " frequency: 0.005}\n",
    ),
    "laid-friction-auto": laid(
        "laid-friction-auto",
        LAID_SURGE % "auto",
        "sweep:\n  analysis.dynamic.excitation.amplitude: [0.05, 2.0]\n"
        "  environment.seabed.friction: [0.0, 0.5]\n",
    ),
    "bent-pinned-time": bent(
        "bent-pinned-time",
        "time",
        "pinned",
        "{end: a, direction: [1.0, 0.0, 0.2], amplitude: 0.005, frequency: 0.2, phase_deg: 180.0}",
    ),
    "bent-pinned-frequency": bent(
        "bent-pinned-frequency",
        "frequency",
        "pinned",
        "{end: a, direction: [1.0, 0.0, 0.2], amplitude: 0.005, frequency: 0.2, phase_deg: 180.0}",
    ),
    "modal-string-water": """\
name: modal-string-water
environment: {fluid: water}
line:
  segments:
    - {length: 10.0, diameter: 0.05, mass_per_length: 3.0, axial_stiffness: 1.0e6}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -5.0]}
  b: {kind: fixed, position: [10.1, 0.0, -5.0]}
analysis:
  static: {nodes: 51}
  modal: {modes: 6, elements: 200}
sweep:
  analysis.modal.include_added_mass: [true, false]
""",
    "spring-linear": """\
name: spring-linear
environment: {fluid: air}
line:
  kind: spring
  length: 10.0
  axial: {law: linear, stiffness: 1000.0}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [10.5, 0.0, 0.0]}
analysis:
  dynamic:
    excitation: {end: b, direction: [1.0, 0.0, 0.0], amplitude: 0.1, frequency: 0.5}
sweep:
  analysis.dynamic.excitation.direction:
    {values: [[1, 0, 0], [0, 1, 0], [-1, 0, 0]], labels: [x, y, minus_x], name: motion}
""",
    "database-turned": """\
name: database-turned
environment:
  fluid: water
  depth: 50.0
line:
  segments:
    - {length: 150.0, diameter: 0.05, mass_per_length: 40.0, axial_stiffness: 2.0e8}
ends:
  a: {kind: fixed, position: [10.0, 20.0, -50.0]}
  b: {kind: fixed, position: [101.92533317427736, 97.1345131623847, -5.0]}
analysis:
  static: {nodes: 41}
  database:
    horizontal_distance: {start: 110.0, stop: 130.0, num: 5}
    height_difference: {start: 41.0, stop: 49.0, num: 5}
""",
    "database-radial": """\
name: database-radial
environment: {fluid: air}
line:
  segments:
    - {length: 20.2, diameter: 0.01, mass_per_length: 1.0, axial_stiffness: 2.0e6}
ends:
  a: {kind: fixed, position: [1.0, 2.0, 3.0]}
  b: {kind: fixed, position: [1.0, 19.320508075688775, 13.0]}
analysis:
  static: {nodes: 41}
  database:
    grid: radial
    distance: {start: 18.0, stop: 20.0, num: 5}
    angle_deg: {start: -30.0, stop: 30.0, num: 5}
""",
}


def mirrored(text: str, name: str) -> str:
    """The same study with ends A and B swapped (the segments' order reversed, the
    attachments and history points moved to ``L - s``, the excitation's end renamed)."""
    doc: dict[str, Any] = yaml.safe_load(text)
    doc["name"] = name
    line = doc["line"]
    length = sum(seg["length"] for seg in line["segments"])
    line["segments"] = line["segments"][::-1]
    for att in line.get("attachments", []):
        att["s"] = length - att["s"]
    doc["ends"] = {"a": doc["ends"]["b"], "b": doc["ends"]["a"]}
    dyn = doc.get("analysis", {}).get("dynamic")
    if dyn:
        excitations = dyn["excitation"]
        for e in excitations if isinstance(excitations, list) else [excitations]:
            e["end"] = {"a": "b", "b": "a"}[e["end"]]
        if "history" in dyn:
            dyn["history"]["points"] = [length - s for s in dyn["history"].get("points", [])]
    return yaml.safe_dump(doc, sort_keys=False)


def turned(text: str, name: str, degrees: float) -> str:
    """The same study in a frame turned by ``degrees`` about z: end positions and
    excitation directions turned, current headings added to."""
    doc: dict[str, Any] = yaml.safe_load(text)
    doc["name"] = name
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))

    def turn(v: list[float]) -> list[float]:
        return [c * v[0] - s * v[1], s * v[0] + c * v[1], v[2]]

    for end in doc["ends"].values():
        if "position" in end:
            end["position"] = turn(end["position"])
    for point in doc.get("environment", {}).get("current", []) or []:
        point["heading_deg"] = point.get("heading_deg", 0.0) + degrees
    dyn = doc.get("analysis", {}).get("dynamic")
    if dyn:
        excitations = dyn["excitation"]
        for e in excitations if isinstance(excitations, list) else [excitations]:
            e["direction"] = turn(e["direction"])
    return yaml.safe_dump(doc, sort_keys=False)
