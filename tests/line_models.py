"""A one-segment :class:`LineModel` for tests that build the line model directly."""

from __future__ import annotations

import numpy as np

from cablestudy.statics.base import LineModel


def one_segment(
    *,
    length: float,
    weight: float,
    mass: float,
    axial_stiffness: float,
    bending_stiffness: float = 0.0,
    diameter: float = 0.1,
    **laws: object,
) -> LineModel:
    """A bare segment [SI units]: no drag, no added mass, no damping, no attachments;
    ``laws`` passes ``axial_law`` through."""
    zero = np.zeros(1)
    return LineModel(
        length=np.array([length]),
        weight=np.array([weight]),
        mass=np.array([mass]),
        axial_stiffness=np.array([axial_stiffness]),
        diameter=np.array([diameter]),
        drag_normal=zero,
        drag_tangential=zero,
        added_mass_normal=zero,
        added_mass_tangential=zero,
        bending_stiffness=np.array([bending_stiffness]),
        damping_ratio=zero,
        attachment_s=np.zeros(0),
        attachment_force=np.zeros((0, 3)),
        attachment_mass=np.zeros(0),
        attachment_volume=np.zeros(0),
        **laws,  # type: ignore[arg-type]
    )
