"""Studies for tests/integration/test_contract_external_more.py: the parts of the study
file the other outside tests leave alone (modal analysis, the quasi-static database,
springs and pulleys, cable laying, time tables, MoorDyn interchange, figures), written
as an OrcaFlex or MoorPy user writes them from DESIGN.md, README.md and docs/ (defaults
left out, realistic values, edge values)."""

from __future__ import annotations

import math

G = 9.80665
RHO = 1025.0

#: a chain hanging straight down in vacuum from a fixed point, its lower end free (a
#: force end with no force): the hanging-chain modes, omega_n = (j_0n / 2) sqrt(g / L)
HANGING_CHAIN = """\
name: hanging-chain
description: 50 m of chain hanging from a crane hook in vacuum, lower end free
environment: {fluid: vacuum}
line:
  segments:
    - {length: 50.0, diameter: 0.05, mass_per_length: 10.0, axial_stiffness: 1.0e10}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: force, force: [0.0, 0.0, 0.0]}
analysis:
  modal: {modes: 6, elements: 200}
"""

#: a neutrally buoyant umbilical (no weight in water) held taut between two pinned
#: ends on a heading of 30 deg: the tensioned pinned beam with added mass,
#: f_n = n / (2 L) sqrt(T / m) sqrt(1 + (n pi / L)^2 EI / T)
TAUT_BEAM = """\
name: taut-beam
description: a neutrally buoyant umbilical held taut, bending on and off
environment: {{fluid: water}}
line:
  segments:
    - {{length: 100.0, diameter: 0.1, mass_per_length: 20.0, weight_in_fluid: 0.0,
       axial_stiffness: 1.0e8, bending_stiffness: 2.0e6}}
ends:
  a: {{kind: fixed, position: [{ax}, {ay}, -30.0]}}
  b: {{kind: fixed, position: [{bx}, {by}, -30.0]}}
analysis:
  static: {{method: discrete, nodes: 41}}
  modal: {{modes: 8, elements: 200}}
sweep:
  analysis.modal.include_bending: [true, false]
"""


def taut_beam(swap: bool = False) -> str:
    """:data:`TAUT_BEAM` 100.1 m between its ends (strain 1e-3, T = 1e5 N), end A at
    (10, 20, -30) (``swap``: the ends exchanged)."""
    c, s = math.cos(math.radians(30.0)), math.sin(math.radians(30.0))
    a, b = (10.0, 20.0), (10.0 + 100.1 * c, 20.0 + 100.1 * s)
    if swap:
        a, b = b, a
    return TAUT_BEAM.format(ax=repr(a[0]), ay=repr(a[1]), bx=repr(b[0]), by=repr(b[1]))


#: a quasi-static database of a chain leg whose plane is turned to +y, on a seabed
#: rising towards +y, in a current across the plane (+x): each grid point is the static
#: solve of end B placed there
DATABASE_TURNED = """\
name: {name}
description: chain leg on a sloping seabed in a cross current{what}
environment:
  fluid: water
  depth: 100.0
  seabed: {{slope_deg: 3.0, slope_heading_deg: 90.0}}
  current:
    - {{z: 0.0, speed: 0.5, heading_deg: 0.0}}
    - {{z: -100.0, speed: 0.2, heading_deg: 0.0}}
line:
  segments:
    - {{length: 250.0, diameter: 0.08, mass_per_length: 40.0, axial_stiffness: 5.0e8}}
ends:
  a: {{kind: fixed, position: [0.0, 0.0, -100.0]}}
  b: {{kind: fixed, position: [0.0, {yb}, -10.0]}}
analysis:
  static: {{nodes: 41}}
{database}"""

DATABASE_GRID = """\
  database:
    horizontal_distance: {start: 190.0, stop: 220.0, num: 4}
    height_difference: {start: 80.0, stop: 95.0, num: 4}
"""

#: a massless spring with a database: refused (docs/guide/cable-laws.md: the database
#: is for catenary lines), it ran with status 0 and every point NaN (status 2)
DATABASE_SPRING = """\
name: database-spring
environment: {fluid: air}
line: {kind: spring, length: 10.0, axial: {law: linear, stiffness: 5000.0}}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [11.0, 0.0, 0.0]}
analysis:
  database:
    horizontal_distance: {start: 10.0, stop: 12.0, num: 5}
    height_difference: {start: -1.0, stop: 1.0, num: 4}
"""

#: springs: slack, a steel wire lifted by a buoy (force end), a polynomial hawser to a
#: mooring end, over a pulley with friction (statics: frictionless)
SPRINGS = """\
name: springs
environment: {fluid: water}
line: {kind: spring, length: 10.0, axial: {law: steel_wire, stiffness: 5000.0, offset: 0.2}}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -30.0]}
  b: {kind: force, force: [0.0, 0.0, 1000.0]}
sweep:
  zip:
    - name: lift
      ends.b.force.0: [0.0, 600.0]
      ends.b.force.2: [1000.0, 800.0]
"""

SPRING_SLACK = """\
name: spring-slack
environment: {fluid: air}
line: {kind: spring, length: 10.0, axial: {law: linear, stiffness: 5000.0}}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [6.0, 0.0, -5.0]}
analysis:
  static: {nodes: 5}
"""

SPRING_PULLEY = """\
name: spring-pulley
environment: {fluid: water}
line:
  kind: spring
  length: 10.0
  axial: {law: linear, stiffness: 5000.0}
  pulleys: [{position: [5.0, 0.0, 0.0], friction_factor: 2.0}]
ends:
  a: {kind: fixed, position: [0.0, 0.0, -1.0]}
  b: {kind: fixed, position: [10.0, 0.0, -1.0]}
sweep:
  ends.b.position.2: [-1.0]
"""

#: a chain over a pulley above the middle of its supports, the pulley moved off the
#: middle, in air: the supports and the pulley carry the line's weight
CATENARY_PULLEY = """\
name: chain-pulley
environment: {fluid: air}
line:
  segments:
    - {length: 120.0, diameter: 0.05, mass_per_length: 20.0, axial_stiffness: 2.0e8}
  pulleys:
    - {position: [50.0, 0.0, 10.0]}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [100.0, 0.0, 0.0]}
analysis:
  static: {nodes: 61}
sweep:
  line.pulleys.0.position.0: [50.0, 40.0]
"""

#: cable laying (vaz-patel): pay-out along the line with no tangential drag and the
#: ship at rest: the shape is the static one, the tension higher by mu V^2 everywhere
LAYING = """\
name: laying
environment: {fluid: water, depth: 500.0}
line:
  segments:
    - {length: 600.0, diameter: 0.04, mass_per_length: 5.0, axial_stiffness: 1.0e12,
       drag_tangential: 0.0}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -300.0]}
  b: {kind: fixed, position: [500.0, 0.0, 0.0]}
analysis:
  static:
    method: shooting
    nodes: 61
    installation: {payout_speed: 2.0}
sweep:
  analysis.static.installation.payout_speed: [0.0, 2.0]
"""

#: a taut tether whose top end is pulled 0.2 m along it by a ramp-and-hold time table
#: over 20 s, run for a fixed 120 s (no period: nothing repeats)
TABLE_PULL = """\
name: table-pull
description: taut tether, top pulled 0.2 m along it over 20 s and held
environment: {fluid: water}
line:
  segments:
    - {length: 100.0, diameter: 0.05, mass_per_length: 8.0, axial_stiffness: 2.0e8,
       damping_ratio: 0.5}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -101.0]}
  b: {kind: fixed, position: [0.0, 0.0, -0.5]}
analysis:
  static: {nodes: 21}
  dynamic:
    method: time
    elements: 20
    duration: 120.0
    history: {points: [100.0], periods: 1.0, samples_per_period: 60}
    excitation:
      end: b
      direction: [0.0, 0.0, 1.0]
      table: [[0.0, 0.0], [10.0, 0.1], [20.0, 0.2], [30.0, 0.2]]
"""

#: a two-segment leg with a clump on a rough seabed in a current, for export / import
EXPORT_LEG = """\
name: export-leg
environment:
  fluid: water
  depth: 150.0
  seabed: {friction: 0.3}
  current:
    - {z: 0.0, speed: 0.6, heading_deg: 30.0}
    - {z: -150.0, speed: 0.1, heading_deg: 30.0}
line:
  segments:
    - {length: 300.0, diameter: 0.137, mass_per_length: 115.0, axial_stiffness: 4.9e8,
       drag_normal: 2.4, drag_tangential: 0.4}
    - {length: 300.0, diameter: 0.1, mass_per_length: 20.0, axial_stiffness: 2.0e8}
  attachments:
    - {s: 300.0, mass: 5000.0, volume: 1.0}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -150.0]}
  b: {kind: fixed, position: [560.0, 0.0, -15.0]}
analysis:
  static: {nodes: 61}
"""


def hanging_chain_frequencies(length: float, count: int) -> list[float]:
    """The hanging chain's natural frequencies [Hz]: f_n = j_0n sqrt(g / L) / (4 pi),
    j_0n the zeros of the Bessel function J_0."""
    from scipy.special import jn_zeros

    return [float(j) * math.sqrt(G / length) / (4.0 * math.pi) for j in jn_zeros(0, count)]


#: a spring whose end B is pulled 0.5 m along it by a ramp-and-hold table, run 50 s
SPRING_TABLE = """\
name: spring-table
environment: {fluid: air}
line: {kind: spring, length: 10.0, axial: {law: linear, stiffness: 5000.0}}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [10.2, 0.0, 0.0]}
analysis:
  dynamic:
    duration: 50.0
    excitation:
      end: b
      direction: [1.0, 0.0, 0.0]
      table: [[0.0, 0.0], [10.0, 0.25], [20.0, 0.5], [30.0, 0.5]]
"""

#: a mooring line's modes for two counts of modes in one study (the mode dimension is
#: the larger count: the smaller case is padded)
MODES_SWEPT = """\
name: modes-swept
environment: {fluid: water}
line:
  segments:
    - {length: 100.0, diameter: 0.05, mass_per_length: 8.0, axial_stiffness: 2.0e8}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -60.0]}
  b: {kind: fixed, position: [80.0, 0.0, -10.0]}
analysis:
  static: {nodes: 21}
  modal: {modes: 2, elements: 40}
sweep:
  analysis.modal.modes: [2, 4]
"""

#: a wire whose law is checked only up to 5 % strain, tabulated out to end distances
#: past 1.05 times its length: those grid points fail (the law's max_strain)
DATABASE_PAST_MAX_STRAIN = """\
name: db-past-max-strain
environment: {fluid: water}
line:
  segments:
    - {length: 120.0, diameter: 0.05, mass_per_length: 10.0,
       axial: {law: linear, stiffness: 6.0e6, max_strain: 0.05}}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -100.0]}
  b: {kind: fixed, position: [100.0, 0.0, -95.0]}
analysis:
  static: {nodes: 21}
  database:
    horizontal_distance: {start: 100.0, stop: 130.0, num: 4}
    height_difference: {start: -10.0, stop: 20.0, num: 4}
"""

#: a taut tendon from an anchor to a hull's keel, the hull heaved 0.2 m by a
#: ramp-and-hold table over a 120 s run (a system: the same motion kernel)
TENDON_TABLE = """\
name: tendon-table
description: a hull heaved 0.2 m by a time table, its tendon taut
environment: {fluid: water}
points:
  anchor: {kind: fixed, position: [0.0, 0.0, -101.0]}
  keel: {kind: body, body: hull, offset: [0.0, 0.0, -1.0]}
bodies:
  hull: {kind: prescribed, position: [0.0, 0.0, 0.5, 0.0, 0.0, 0.0]}
lines:
  tendon: {a: anchor, b: keel, segments: [{length: 100.0, diameter: 0.05,
           mass_per_length: 8.0, axial_stiffness: 2.0e8, damping_ratio: 0.5}]}
analysis:
  dynamic:
    method: time
    elements: 10
    duration: 120.0
    history: {periods: 0.25, samples_per_period: 8}
    excitation: {body: hull, dof: heave, table: [[0.0, 0.0], [10.0, 0.1], [20.0, 0.2], [30.0, 0.2]]}
"""
