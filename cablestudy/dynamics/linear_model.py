"""The frequency-domain solver's input from the shared line model.

:func:`linear_line` builds a :class:`~cablestudy.dynamics.frequency.LinearLine` about a
static shape sampled at the nodes: mass, tangent stiffness and structural damping are
the time-domain model's own tangents at rest in that shape
(:func:`cablestudy.dynamics.modal.tangents`, which evaluates
:func:`cablestudy.dynamics.model.assemble`): axial and geometric stiffness, bending with
pinned or clamped ends, the seabed contact spring and dashpot, sticking seabed friction
(for small motions static friction keeps the laid line from sliding: friction is
linearised as its stick spring), the axial strain-rate and transverse structural
damping, added mass of the line and of lumped bodies. What it adds: the nodal drag
coefficients ``1/2 rho C_N d l`` and ``1/2 rho pi C_T d l`` over the node's tributary
length ``l``, the current at the nodes and the node tangents (the chord of the two
neighbouring nodes), for the solver's own drag linearisation. Both end nodes are
prescribed (held, or moved by the excitation), as in the time domain.
"""

from __future__ import annotations

import functools
import math
from dataclasses import replace

import numpy as np
import scipy.sparse as sp

from ..physics.current import current_velocity
from ..statics.base import EndCondition
from .frequency import LinearLine
from .modal import ModalProblem, _segment_index, element_tangent, tangents


def linear_line(problem: ModalProblem) -> LinearLine:
    """The linearised line about ``problem.static`` (its samples are the nodes), with
    both end nodes prescribed. ``problem.include_added_mass`` and
    ``include_bending`` apply as in modal analysis."""
    held = EndCondition(kind="fixed")
    prob = replace(problem, end_a=held, end_b=held)
    line, medium, st = prob.line, prob.medium, prob.static
    s, pos = np.asarray(st.s, dtype=float), np.asarray(st.position, dtype=float)
    n = s.size
    l0 = np.diff(s)
    chord = np.diff(pos, axis=0)
    t = chord / np.linalg.norm(chord, axis=1)[:, None]
    seg = _segment_index(line, 0.5 * (s[:-1] + s[1:]))
    # the tension response of an element is its law's tangent at the static strain
    ea = element_tangent(line, s, 0.5 * (st.tension[:-1] + st.tension[1:]))
    c_axial = line.damping_ratio[seg] * l0 * np.sqrt(line.axial_stiffness[seg] * line.mass[seg])

    def lump(per_length: np.ndarray) -> np.ndarray:
        half = 0.5 * per_length[seg] * l0
        out = np.zeros(n)
        out[:-1] += half
        out[1:] += half
        return out

    rho = medium.density
    drag_n = lump(0.5 * rho * line.drag_normal * line.diameter)
    drag_t = lump(0.5 * rho * math.pi * line.drag_tangential * line.diameter)
    drag_b = body_drag(line, prob.extras, s, rho)
    lo = np.maximum(np.arange(n) - 1, 0)
    hi = np.minimum(np.arange(n) + 1, n - 1)
    tangent = pos[hi] - pos[lo]
    tangent /= np.linalg.norm(tangent, axis=1)[:, None]

    mass, stiffness, damping = tangents(prob)
    return LinearLine(
        s=s,
        position=pos,
        mass=mass,
        stiffness=stiffness,
        damping=damping,
        rest_length=l0,
        direction=t,
        axial_stiffness=ea,
        axial_damping=c_axial,
        tension=0.5 * (st.tension[:-1] + st.tension[1:]),
        end_force=np.stack([np.asarray(st.force_a), np.asarray(st.force_b)]),
        drag_normal=drag_n,
        drag_tangential=drag_t,
        current=current_velocity(pos[:, 2], medium.current_z, medium.current_velocity),
        tangent=tangent,
        free_basis=held_ends_basis(n),
        drag_body=drag_b if np.any(drag_b > 0.0) else None,
    )


def body_drag(line: object, extras: object, s: np.ndarray, rho: float) -> np.ndarray:
    """[kg/m] (n,) the lumped bodies' drag coefficients ``1/2 rho C_D A`` at nodes ``s``
    [m]: each body's shared between the two nodes of its element in proportion to its
    place along it, as the time-domain model lumps it (:func:`cablestudy.dynamics.model.
    build_model`)."""
    n = s.size
    out = np.zeros(n)
    s_att = np.asarray(getattr(line, "attachment_s", np.zeros(0)), dtype=float)
    area = getattr(extras, "attachment_drag_area", None) if extras is not None else None
    if s_att.size == 0 or area is None or np.size(area) == 0 or n < 2:
        return out
    area = np.asarray(area, dtype=float)
    l0 = np.diff(s)
    for k in range(s_att.size):
        e = int(np.clip(np.searchsorted(s, s_att[k], side="right") - 1, 0, n - 2))
        xi = (s_att[k] - s[e]) / l0[e]
        out[e] += (1.0 - xi) * 0.5 * rho * area[k]
        out[e + 1] += xi * 0.5 * rho * area[k]
    return out


def held_ends_basis(n: int) -> sp.csr_matrix:
    """The free basis (3n, 3 (n - 2)) of ``n`` nodes whose two end nodes are held
    (:func:`~cablestudy.dynamics.modal.node_bases` with fixed ends: no column at an end
    node, the three axes at every other node, in node order), with each inner node's
    identity block stored whole, its zeros too, as scipy stores the blocks given as
    coordinates."""
    data, indices, indptr = _held_ends_arrays(n)
    return sp.csr_matrix(
        (data.copy(), indices.copy(), indptr.copy()), shape=(3 * n, 3 * max(n - 2, 0))
    )


@functools.lru_cache(maxsize=16)
def _held_ends_arrays(n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    inner = max(n - 2, 0)
    per_row = np.zeros(3 * n, dtype=np.int32)
    per_row[3 : 3 + 3 * inner] = 3
    indptr = np.concatenate(([0], np.cumsum(per_row))).astype(np.int32)
    indices = np.repeat(np.arange(3 * inner, dtype=np.int32).reshape(inner, 1, 3), 3, axis=1)
    data = np.tile(np.eye(3).ravel(), inner)
    for a in (data, indices, indptr):
        a.flags.writeable = False
    return data, indices.ravel(), indptr
