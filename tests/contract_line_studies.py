"""One-line studies written from outside (not copies of configs/) for
tests/integration/test_contract_external_line.py: each a YAML text as a user would
write it, small enough to run in well under a second. Together they vary the fluid
(air, water, {density}), depth or none, seabed slope and friction, one-point, sheared
and turning currents, mass_per_length and weight_in_fluid, several segments,
attachments (force, clump, buoy), fixed, towing and mooring ends, every static method,
modal, and dynamics by methods time, frequency and auto (frequency or period), swept by
lists and {start, stop, num}, on two axes, by keys deep in segments, attachments and
current, by list indices, by a labelled vector, and by {start, stop, step} with a
swept node count."""

from __future__ import annotations

STUDIES: dict[str, str] = {
    "air-analytic": """\
name: air-analytic
environment: {fluid: air}
line:
  segments:
    - {length: 120.0, diameter: 0.03, mass_per_length: 5.0, axial_stiffness: 1.0e8}
ends:
  a: {kind: fixed, position: [10.0, 5.0, 30.0]}
  b: {kind: fixed, position: [110.0, 5.0, 10.0]}
analysis:
  static: {method: analytic, nodes: 41}
sweep:
  ends.b.position.0: [90.0, 110.0]
""",
    "mooring-friction": """\
name: mooring-friction
environment:
  fluid: water
  depth: 80.0
  seabed: {friction: 0.4}
line:
  segments:
    - {length: 300.0, diameter: 0.08, mass_per_length: 120.0, axial_stiffness: 5.0e8}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -80.0]}
  b: {kind: mooring, force: [60000.0, 30000.0], z: -10.0}
analysis:
  static: {nodes: 61}
sweep:
  environment.seabed.friction: {start: 0.0, stop: 0.8, num: 3}
""",
    "density-shooting-sheared": """\
name: density-shooting-sheared
environment:
  fluid: {density: 1020.0}
  depth: 150.0
  current:
    - {z: 0.0, speed: 1.0, heading_deg: 30.0}
    - {z: -150.0, speed: 0.2, heading_deg: 30.0}
line:
  segments:
    - {length: 250.0, diameter: 0.05, weight_in_fluid: 150.0, axial_stiffness: 2.0e8}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -150.0]}
  b: {kind: fixed, position: [180.0, 0.0, -5.0]}
analysis:
  static: {method: shooting, nodes: 51}
sweep:
  environment.current.0.speed: {start: 0.5, stop: 1.5, num: 3}
""",
    "segments-attachments-slope": """\
name: segments-attachments-slope
environment:
  fluid: water
  depth: 200.0
  seabed: {slope_deg: 3.0, slope_heading_deg: 45.0, friction: 0.2}
line:
  segments:
    - {length: 150.0, diameter: 0.1, weight_in_fluid: 1200.0, axial_stiffness: 8.0e8}
    - {length: 200.0, diameter: 0.12, mass_per_length: 9.0, axial_stiffness: 1.0e8}
    - {length: 50.0, diameter: 0.1, weight_in_fluid: 1200.0, axial_stiffness: 8.0e8}
  attachments:
    - {s: 250.0, mass: 2000.0}
    - {s: 300.0, volume: 3.0}
    - {s: 200.0, force: [500.0, 0.0, -1000.0]}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -200.0]}
  b: {kind: fixed, position: [300.0, 50.0, -15.0]}
analysis:
  static: {nodes: 81}
sweep:
  line.attachments.0.mass: [1000.0, 3000.0]
  line.segments.0.length: {start: 140.0, stop: 160.0, num: 2}
""",
    "towing-current": """\
name: towing-current
environment:
  fluid: water
  current:
    - {z: 0.0, speed: 1.5, heading_deg: 180.0}
line:
  segments:
    - {length: 200.0, diameter: 0.04, mass_per_length: 4.0, axial_stiffness: 8.0e7}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: force, force: [-2000.0, 0.0, -3000.0]}
analysis:
  static: {nodes: 51}
sweep:
  ends.b.force.0: [-1000.0, -4000.0]
  environment.current.0.heading_deg: [180.0, 150.0]
""",
    "discrete-two-segments": """\
name: discrete-two-segments
environment: {fluid: water}
line:
  segments:
    - {length: 60.0, diameter: 0.1, mass_per_length: 30.0, axial_stiffness: 3.0e8}
    - {length: 60.0, diameter: 0.12, mass_per_length: 40.0, axial_stiffness: 3.0e8}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -5.0]}
  b: {kind: fixed, position: [100.0, 0.0, -20.0]}
analysis:
  static: {method: discrete, nodes: 41}
""",
    "modal": """\
name: modal
environment: {fluid: water}
line:
  segments:
    - {length: 100.0, diameter: 0.05, mass_per_length: 8.0, axial_stiffness: 2.0e8}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -10.0]}
  b: {kind: fixed, position: [95.0, 0.0, -20.0]}
analysis:
  static: {nodes: 31}
  modal: {modes: 4}
sweep:
  ends.b.position.2: [-20.0, -40.0]
""",
    "time-period": """\
name: time-period
environment: {fluid: water}
line:
  segments:
    - {length: 100.0, diameter: 0.05, mass_per_length: 8.0, axial_stiffness: 2.0e8}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -60.0]}
  b: {kind: fixed, position: [90.0, 0.0, -10.0]}
analysis:
  static: {nodes: 21}
  dynamic:
    excitation: {end: b, direction: [0.0, 0.0, 1.0], amplitude: 0.5, period: 8.0}
    method: time
    elements: 20
sweep:
  analysis.dynamic.excitation.amplitude: [0.2, 0.8]
""",
    "frequency-range": """\
name: frequency-range
environment: {fluid: water, depth: 100.0}
line:
  segments:
    - {length: 120.0, diameter: 0.05, mass_per_length: 8.0, axial_stiffness: 2.0e8}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -100.0]}
  b: {kind: fixed, position: [80.0, 0.0, -10.0]}
analysis:
  static: {nodes: 21}
  dynamic:
    excitation: {end: b, direction: [1.0, 0.0, 0.0], amplitude: 0.3, frequency: 0.1}
    method: frequency
    elements: 30
sweep:
  analysis.dynamic.excitation.frequency: {start: 0.05, stop: 0.15, num: 3}
""",
    "auto-period-index": """\
name: auto-period-index
environment:
  fluid: water
  depth: 60.0
  current:
    - {z: 0.0, speed: 0.3, heading_deg: 90.0}
line:
  segments:
    - {length: 70.0, diameter: 0.04, mass_per_length: 6.0, axial_stiffness: 1.0e8}
  attachments:
    - {s: 35.0, force: [0.0, 0.0, -200.0]}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -30.0]}
  b: {kind: fixed, position: [65.0, 0.0, -5.0]}
analysis:
  static: {nodes: 15}
  dynamic:
    excitation: {end: b, direction: [1.0, 0.0, 1.0], amplitude: 0.2, period: 10.0}
    elements: 14
sweep:
  analysis.dynamic.excitation.period: {start: 6.0, stop: 12.0, num: 2}
  line.attachments.0.force.2: [-200.0, -400.0]
""",
    "towed-modal-labels": """\
name: towed-modal-labels
environment: {fluid: water}
line:
  segments:
    - {length: 150.0, diameter: 0.03, weight_in_fluid: 20.0, mass_per_length: 3.0,
       axial_stiffness: 5.0e7}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: force, force: [-500.0, 0.0, -1000.0]}
analysis:
  static: {nodes: 31, method: shooting}
  modal: {modes: 3}
sweep:
  ends.b.force: {values: [[-500.0, 0.0, -1000.0], [-500.0, 300.0, -1000.0]],
                 labels: [inline, skew]}
""",
    "turning-current-mooring-dynamic": """\
name: turning-current-mooring-dynamic
environment:
  fluid: water
  depth: 100.0
  current:
    - {z: 0.0, speed: 0.5, heading_deg: 0.0}
    - {z: -100.0, speed: 0.2, heading_deg: 90.0}
line:
  segments:
    - {length: 250.0, diameter: 0.07, mass_per_length: 100.0, axial_stiffness: 4.0e8}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -100.0]}
  b: {kind: mooring, force: [50000.0, 0.0], z: -10.0}
analysis:
  static: {nodes: 26}
  dynamic:
    excitation: {end: b, direction: [1.0, 0.0, 0.0], amplitude: 1.0, frequency: 0.08}
    method: time
    elements: 25
""",
    "nodes-and-length-steps": """\
name: nodes-and-length-steps
environment: {fluid: water, depth: 50.0}
line:
  segments:
    - {length: 100.0, diameter: 0.03, mass_per_length: 10.0, axial_stiffness: 1.0e8}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -50.0]}
  b: {kind: fixed, position: [80.0, 0.0, -20.0]}
analysis:
  static: {nodes: 11}
  modal: {modes: 2}
  dynamic:
    excitation: {end: b, direction: [1.0, 0.0, 0.0], amplitude: 0.5, frequency: 0.1}
    elements: 20
sweep:
  analysis.static.nodes: [11, 21]
  line.segments.0.length: {start: 100.0, stop: 105.0, step: 5.0}
""",
}

#: a two-segment line with a clump, anchored on the seabed (test_swapping_ends_...)
FORWARD = """\
name: forward
environment:
  fluid: water
  depth: 120.0
line:
  segments:
    - {length: 100.0, diameter: 0.08, mass_per_length: 60.0, axial_stiffness: 4.0e8}
    - {length: 80.0, diameter: 0.05, mass_per_length: 10.0, axial_stiffness: 1.0e8}
  attachments:
    - {s: 122.0, mass: 500.0}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -120.0]}
  b: {kind: fixed, position: [120.0, 0.0, -10.0]}
analysis:
  static: {nodes: 37, method: METHOD}
"""
#: the same line from B to A: segments and attachment reversed, s -> 180 - s
REVERSED = (
    FORWARD.replace("name: forward", "name: reversed")
    .replace(
        "    - {length: 100.0, diameter: 0.08, mass_per_length: 60.0, axial_stiffness: 4.0e8}\n"
        "    - {length: 80.0, diameter: 0.05, mass_per_length: 10.0, axial_stiffness: 1.0e8}\n",
        "    - {length: 80.0, diameter: 0.05, mass_per_length: 10.0, axial_stiffness: 1.0e8}\n"
        "    - {length: 100.0, diameter: 0.08, mass_per_length: 60.0, axial_stiffness: 4.0e8}\n",
    )
    .replace("{s: 122.0, mass: 500.0}", "{s: 58.0, mass: 500.0}")
    .replace("a: {kind: fixed, position: [0.0, 0.0, -120.0]}", "a: {kind: fixed, position: X}")
    .replace("b: {kind: fixed, position: [120.0, 0.0, -10.0]}", "b: {kind: fixed, position: Y}")
    .replace("position: X", "position: [120.0, 0.0, -10.0]")
    .replace("position: Y", "position: [0.0, 0.0, -120.0]")
)

#: end B moved slowly (test_slow_end_motion_...)
QUASI_STATIC = """\
name: quasi-static
environment: {fluid: water}
line:
  segments:
    - {length: 100.0, diameter: 0.03, mass_per_length: 10.0, axial_stiffness: 1.0e8}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -10.0]}
  b: {kind: fixed, position: [90.0, 0.0, -20.0]}
analysis:
  static: {nodes: 21}
  modal: {modes: 1}
  dynamic:
    excitation: {end: b, direction: [1.0, 0.0, 0.0], amplitude: 1.0, frequency: 0.005}
    method: time
    elements: 40
"""
