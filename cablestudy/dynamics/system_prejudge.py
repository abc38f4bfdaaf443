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
unstretched arc lengths (both verified nonlinear equilibria).

Why a line failing it cannot be linear at any frequency: the quasi-static shape change
is the geometry the line's restoring forces (weight, tension, stretch) impose between
the motion's extremes, a property of the stiffness term of the frequency domain's
operator ``K - w^2 M + i w C``, which that model keeps at every frequency as the
tangent at the static state. The limit on amplitude/sag is where the terms of order
(shape change / sag)^2 that tangent drops reach the accepted size; a line whose
equilibrium shape alone changes by more than twice the limit leaves the range where
that tangent describes its restoring forces, and inertia and damping, which add to
the stiffness and do not replace it, cannot bring the dropped terms back. The
decision is taken only with that margin (:data:`MARGIN`): a line's quasi-static
measure above MARGIN x the limit sends the case to the time domain at once; anything
less (or a system this check cannot solve) goes through the frequency domain and its
post-solve check exactly as before.

Checked against the post-solve check on every system case of the tests and configs
with ``method: auto`` (the report of the change that added it): MoorPy's case8 at
0.1 Hz, surge 0.1 m (frequency domain trusted; quasi-static 0.014 = 0.19 of the limit,
the frequency domain's own measure 0.030, 2.1 times it), surge 2 m (time domain;
quasi-static 0.376 = 5.0 times the limit, the frequency domain's 2.78, 7.4 times it:
decided here), heave 1 m (time domain; quasi-static 0.87 of the limit: left to the
frequency domain, whose measure 1.2 is 18 times it); at 2 to 20 elements a line the
same. MoorDyn's lines.txt (legs on the seabed) is not judged here. On every case the
frequency domain's measure was at least twice the quasi-static one, never below it.
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
