"""The frequency-domain solver's input from the shared line model.

:func:`linear_line` builds a :class:`~cablestudy.dynamics.frequency_model.LinearLine` about a
static shape sampled at the nodes: mass, tangent stiffness and structural damping are
the time-domain model's own tangents at rest in that shape
(:func:`cablestudy.dynamics.modal.tangents_of`, which evaluates
:func:`cablestudy.dynamics.assembly.assemble`): axial and geometric stiffness, bending with
pinned or clamped ends, the seabed contact spring and dashpot, sticking seabed friction
(for small motions static friction keeps the laid line from sliding: friction is
linearised as its stick spring), the axial strain-rate and transverse structural
damping, added mass of the line and of lumped bodies. What it adds: the nodal drag
coefficients ``1/2 rho C_N d l`` and ``1/2 rho pi C_T d l`` over the node's tributary
length ``l``, the current at the nodes and the node tangents (the chord of the two
neighbouring nodes), and the lumped bodies' drag ``1/2 rho C_D A`` as the shared model
lumps it, for the solver's own drag linearisation. Both end nodes are
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
from .frequency_model import LinearLine
from .modal import ModalProblem, _segment_index, element_tangent, shared_model, tangents_of


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
    lo = np.maximum(np.arange(n) - 1, 0)
    hi = np.minimum(np.arange(n) + 1, n - 1)
    tangent = pos[hi] - pos[lo]
    tangent /= np.linalg.norm(tangent, axis=1)[:, None]

    disc, x = shared_model(prob)
    mass, stiffness, damping = tangents_of(disc, x)
    # the bodies' drag 1/2 rho C_D A, lumped on their elements' nodes by the shared
    # model, as the time domain has it
    drag_b = np.asarray(disc.body_drag, dtype=float)
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
