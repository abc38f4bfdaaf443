"""MoorDyn's seabed contact in cablestudy's terms, and back.

MoorDyn presses a node touching its flat seabed up with ``(kBot delta - cBot v_z) d l``
per node: a stiffness ``kBot`` [Pa/m] and damping ``cBot`` [Pa s/m] per unit of the
line's diameter ``d`` and length ``l``. cablestudy's contact (``environment.seabed``) is
a stiffness per length, ``stiffness`` [N/m^2] = kBot d, and a damping given as a
fraction of each node's critical damping on that spring, ``damping_ratio`` = c /
(2 sqrt(k m)) with ``c`` = cBot d and ``m`` the mass per length with normal added mass.
One study has one contact stiffness; MoorDyn's scales with each line type's diameter:
the mapping uses a reference segment (the one of largest diameter) and says so.
"""

from __future__ import annotations

import math

#: MoorDyn's defaults when a file gives no kBot / cBot [Pa/m], [Pa s/m]
DEFAULT_KBOT = 3.0e6
DEFAULT_CBOT = 3.0e5


def from_moordyn(kbot: float, cbot: float, *, diameter: float, mass: float) -> tuple[float, float]:
    """(stiffness per length [N/m^2], damping ratio [-]) of MoorDyn's ``kbot`` [Pa/m] and
    ``cbot`` [Pa s/m] on a segment of ``diameter`` [m] and ``mass`` [kg/m] (with added
    mass)."""
    stiffness = kbot * diameter
    return stiffness, cbot * diameter / (2.0 * math.sqrt(stiffness * mass))


def to_moordyn(
    stiffness: float, damping_ratio: float, *, diameter: float, mass: float
) -> tuple[float, float]:
    """(kBot [Pa/m], cBot [Pa s/m]) of a contact ``stiffness`` [N/m^2] and
    ``damping_ratio`` [-] on a segment of ``diameter`` [m] and ``mass`` [kg/m]."""
    return stiffness / diameter, 2.0 * damping_ratio * math.sqrt(stiffness * mass) / diameter
