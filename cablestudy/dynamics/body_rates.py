"""Small rotations of a body given in its Euler angles: the global rotation vector of a
change of the angles about a turned body.

A body's orientation is R = Rz(yaw) Ry(pitch) Rx(roll) (docs/guide/systems.md). A small
change (d roll, d pitch, d yaw) of the angles turns the body by the global rotation
vector ``w = E (d roll, d pitch, d yaw)`` (dR R^T = [w]x), each angle's change about its
own axis as the composition places it:

    w = d yaw e_z + d pitch Rz(yaw) e_y + d roll Rz(yaw) Ry(pitch) e_x.

At zero angles E is the identity: the changes of the angles are the rotation vector.
The frequency domain moves a body's points by ``w x a`` (first order), so with this
matrix it linearises the time domain's exact motion about any static orientation.

Pure: arrays in, arrays out (radians).
"""

from __future__ import annotations

import numpy as np


def euler_rate_matrix(angles: np.ndarray) -> np.ndarray:
    """E (3, 3) of a body at ``angles`` = (roll, pitch, yaw) [rad]: the global rotation
    vector of the changes (d roll, d pitch, d yaw) is ``E @ (d roll, d pitch, d yaw)``."""
    _, pitch, yaw = (float(a) for a in angles)
    cp, sp, cy, sy = np.cos(pitch), np.sin(pitch), np.cos(yaw), np.sin(yaw)
    return np.array(
        [
            [cy * cp, -sy, 0.0],
            [sy * cp, cy, 0.0],
            [-sp, 0.0, 1.0],
        ]
    )


def rotation_vector(angles: np.ndarray, changes: np.ndarray) -> np.ndarray:
    """The global rotation vector (..., 3) of the (complex) angle ``changes`` (..., 3)
    [rad] of a body at ``angles`` (roll, pitch, yaw); the changes themselves, unchanged,
    at zero angles."""
    changes = np.asarray(changes)
    if not np.any(np.asarray(angles, dtype=float)):
        return changes
    return changes @ euler_rate_matrix(angles).T
