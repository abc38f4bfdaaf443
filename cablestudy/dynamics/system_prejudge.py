"""The geometric check of ``method: auto`` for a system decided before the frequency
domain is built (issue 24): the lines' quasi-static shape change over the motion's
amplitude against their sag. Pure: arrays in, numbers out.

What the post-solve check measures (:mod:`cablestudy.dynamics.system_validity`): per
line the largest amplitude of its nodes' displacement relative to the motion of its
chord, ``u(s) - (1 - xi) u_A - xi u_B`` (``xi`` the node's share of the unstretched
length), over the static sag; above ``max_amplitude_sag_ratio`` the terms of order
(displacement / sag)^2 the linearisation drops are no longer small, and the time
domain runs.

Here the same measure is taken on the quasi-static response: the system's static
equilibrium solved again with the moved body at its two extreme positions (static
position plus and minus the amplitude in the moved degree of freedom), ``u`` the
difference of each line's static shape there and in the static state, at the same
unstretched arc lengths. Why a line failing it cannot be linear at the motion's
frequency: the quasi-static shape change is exact (each shape is a verified nonlinear
equilibrium) and is the part of the response the line's geometric stiffness alone
imposes; a linear response ``u = H(w) X`` whose amplitude stayed within the limit would
have to cancel most of it by inertia and damping, which in the frequency domain's own
model of the line would put the line above its first transverse resonance, where the
linearisation's geometric terms (the change of the line's shape against its sag) are
larger still, not smaller. So the decision is taken only with a margin: a line's
quasi-static measure above :data:`MARGIN` times the limit sends the case to the time
domain at once; anything less (or a system this check cannot solve) goes through the
frequency domain and its post-solve check as before.

Measured (``tests/unit/test_system_prejudge.py`` and the report of the change that
added it): on MoorPy's case8 surged at 0.1 Hz with 3 to 20 elements a line, the
frequency domain's measure on the bridles is 2.1 to 7.5 times the quasi-static one
(0.1 m: 0.014 quasi-static, 0.03 by the frequency domain; 2 m: 0.376, 2.83), so the
margin of 2 leaves every case the post-solve check trusts far below the threshold.
"""

from __future__ import annotations

import numpy as np

#: the quasi-static measure over ``max_amplitude_sag_ratio`` above which the time
#: domain runs without the frequency domain (module docstring)
MARGIN = 2.0


def line_sags(position: np.ndarray) -> np.ndarray:
    """Each line's largest distance [m] from the chord of its two end points:
    ``position`` (M, n, 3) -> (M,), :func:`cablestudy.dynamics.validity.sag` of each."""
    chord = position[:, -1] - position[:, 0]
    length = np.linalg.norm(chord, axis=1)
    rel = position - position[:, :1]
    unit = chord / np.where(length > 0.0, length, 1.0)[:, None]
    along = np.einsum("mnc,mc->mn", rel, unit)
    off = np.linalg.norm(rel - along[..., None] * unit[:, None], axis=2)
    return np.where(length > 0.0, np.max(off, axis=1), np.max(np.linalg.norm(rel, axis=2), axis=1))


def shape_change_ratios(s: np.ndarray, static: np.ndarray, moved: np.ndarray) -> np.ndarray:
    """Per line the largest quasi-static shape change over its sag (module docstring).

    ``s`` (M, n) [m] unstretched arc lengths of the nodes; ``static`` (M, n, 3) [m] the
    static shapes there; ``moved`` (K, M, n, 3) [m] the shapes with the body at its K
    extreme positions. The deformation relative to the chord's motion and the sag are
    those of :func:`cablestudy.dynamics.system_validity.system_measures` (a straight
    line, sag below 1e-9 of its length, over its length instead). Returns (M,)."""
    u = moved - static[None]
    xi = ((s - s[:, :1]) / (s[:, -1:] - s[:, :1]))[None, ..., None]
    deformation = u - (1.0 - xi) * u[:, :, :1] - xi * u[:, :, -1:]
    amp = np.max(np.sqrt(np.sum(deformation**2, axis=3)), axis=(0, 2))
    length = s[:, -1] - s[:, 0]
    d = line_sags(static)
    return amp / np.where(d > 1e-9 * length, d, length)


__all__ = ["MARGIN", "line_sags", "shape_change_ratios"]
