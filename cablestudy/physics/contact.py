"""Seabed contact laws shared by the line model and the interchange."""

from __future__ import annotations

import numpy as np

#: static penetration [m] of the heaviest segment that sets the default contact stiffness
DEFAULT_PENETRATION = 1e-3


def default_seabed_stiffness(weight: np.ndarray) -> float:
    """Default normal contact stiffness per length [N/m^2]: the heaviest segment's
    ``weight`` in the fluid per length [N/m] over a 1 mm penetration, at least 1 kPa."""
    return max(float(np.max(weight)) / DEFAULT_PENETRATION, 1e3)
