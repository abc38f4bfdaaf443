"""Constitutive laws behind one interface: tension as a function of strain and its
derivative. A law is a frozen dataclass with ``tension(strain)`` [N] and
``stiffness(strain)`` = dT/d(strain) [N]; laws are found by name in :data:`LAWS`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np


class ConstitutiveLaw(Protocol):
    def tension(self, strain: np.ndarray) -> np.ndarray: ...

    def stiffness(self, strain: np.ndarray) -> np.ndarray: ...


@dataclass(frozen=True)
class LinearElastic:
    """Hooke's law T = EA * strain (dodaran-park seed eq. 5). With ``tension_only`` a
    segment in compression carries no force (aqwa seed: linear tension-only spring)."""

    axial_stiffness: float
    tension_only: bool = True

    def tension(self, strain: np.ndarray) -> np.ndarray:
        t = self.axial_stiffness * np.asarray(strain, dtype=float)
        return np.maximum(t, 0.0) if self.tension_only else t

    def stiffness(self, strain: np.ndarray) -> np.ndarray:
        strain = np.asarray(strain, dtype=float)
        k = np.full(strain.shape, self.axial_stiffness)
        return np.where(strain > 0.0, k, 0.0) if self.tension_only else k


LAWS = {"linear": LinearElastic}
