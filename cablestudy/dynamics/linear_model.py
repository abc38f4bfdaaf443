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
from collections.abc import Sequence
from dataclasses import replace

import numpy as np
import scipy.sparse as sp

from ..physics.current import current_velocity
from ..statics.base import EndCondition
from .discrete_line import discretise_nodes, lump_on_nodes, same_inputs
from .frequency_model import LinearLine
from .modal import (
    ModalProblem,
    _segment_index,
    default_extras,
    element_strain,
    element_tangent,
    filled_csr,
    tangents_of,
)


def linear_line(problem: ModalProblem) -> LinearLine:
    """The linearised line about ``problem.static`` (its samples are the nodes), with
    both end nodes prescribed. ``problem.include_added_mass`` and
    ``include_bending`` apply as in modal analysis (:func:`linear_lines` of the one
    line, its ends held)."""
    held = EndCondition(kind="fixed")
    return linear_lines([replace(problem, end_a=held, end_b=held)])[0]


def linear_lines(problems: Sequence[ModalProblem]) -> list[LinearLine]:
    """The linearised line of each problem (a system's lines, or the one line of
    :func:`linear_line`), about its static shape: the shared model's tangents
    (:func:`~.modal.shared_model`'s changes: rest lengths from the static tension's
    strain, added mass and bending as the problem asks, laid nodes a nanometre into the
    seabed), with the solver's own drag coefficients, current and node tangents. Lines
    alike in every input of their discretisation (line, medium, dynamic extras, node arc
    lengths: a spread's legs, a spar's bridles) share it (it depends on those alone, not
    on where the line lies), and each line's element segments and strains are found
    once."""
    made: list[tuple[tuple, object]] = []
    out = []
    for problem in problems:
        line, medium, st = problem.line, problem.medium, problem.static
        s, pos = np.asarray(st.s, dtype=float), np.asarray(st.position, dtype=float)
        n = s.size
        extras = problem.extras or default_extras(line, medium)
        key = (s, medium, extras, line)  # the cheap inputs first: unlike lines part soon
        disc = next((d for k, d in made if same_inputs(k, key)), None)
        if disc is None:
            disc = discretise_nodes(line, medium, s, extras)
            made.append((key, disc))
        # modal.shared_model's changes, the static tension's strain found once
        l0 = np.diff(s)
        seg = _segment_index(line, 0.5 * (s[:-1] + s[1:]))
        T_e = 0.5 * (st.tension[:-1] + st.tension[1:])
        strain = element_strain(line, s, T_e, seg)
        chord_length = np.linalg.norm(np.diff(pos, axis=0), axis=1)
        changes: dict = {"rest_length": chord_length / (1.0 + strain), "has_drag": False}
        if not problem.include_added_mass:
            zero = np.zeros(disc.n_nodes)  # type: ignore[attr-defined]
            changes.update(added_mass_normal=zero, added_mass_tangential=zero, body_added_mass=zero)
        if not problem.include_bending:
            changes["bending"] = np.zeros(disc.n_nodes)  # type: ignore[attr-defined]
        here = replace(disc, **changes)  # type: ignore[type-var]
        x = pos.copy()
        if here.has_seabed:
            gap = x @ here.seabed_normal - here.seabed_offset
            laid = gap <= 1e-6 * max(float(s[-1]), 1.0)
            x[laid] -= np.outer(gap[laid] + 1e-9, here.seabed_normal)
        # linear_line's own
        chord = np.diff(pos, axis=0)
        t = chord / np.linalg.norm(chord, axis=1)[:, None]
        ea = element_tangent(line, s, T_e, seg, strain)
        c_axial = line.damping_ratio[seg] * l0 * np.sqrt(line.axial_stiffness[seg] * line.mass[seg])
        rho = medium.density
        drag_n = lump_on_nodes(0.5 * rho * line.drag_normal * line.diameter, seg, l0, n)
        drag_t = lump_on_nodes(
            0.5 * rho * math.pi * line.drag_tangential * line.diameter, seg, l0, n
        )
        lo = np.maximum(np.arange(n) - 1, 0)
        hi = np.minimum(np.arange(n) + 1, n - 1)
        tangent = pos[hi] - pos[lo]
        tangent /= np.linalg.norm(tangent, axis=1)[:, None]
        mass, stiffness, damping = tangents_of(here, x)
        drag_b = np.asarray(here.body_drag, dtype=float)
        out.append(
            LinearLine(
                s=s,
                position=pos,
                mass=mass,
                stiffness=stiffness,
                damping=damping,
                rest_length=l0,
                direction=t,
                axial_stiffness=ea,
                axial_damping=c_axial,
                tension=T_e,
                end_force=np.stack([np.asarray(st.force_a), np.asarray(st.force_b)]),
                drag_normal=drag_n,
                drag_tangential=drag_t,
                current=current_velocity(pos[:, 2], medium.current_z, medium.current_velocity),
                tangent=tangent,
                free_basis=held_ends_basis(n),
                drag_body=drag_b if np.any(drag_b > 0.0) else None,
            )
        )
    return out


def held_ends_basis(n: int) -> sp.csr_matrix:
    """The free basis (3n, 3 (n - 2)) of ``n`` nodes whose two end nodes are held
    (:func:`~cablestudy.dynamics.modal.node_bases` with fixed ends: no column at an end
    node, the three axes at every other node, in node order), with each inner node's
    identity block stored whole, its zeros too, as scipy stores the blocks given as
    coordinates."""
    held = _held_ends(n)
    return filled_csr(held, held.data.copy())


@functools.lru_cache(maxsize=16)
def _held_ends(n: int) -> sp.csr_matrix:
    """:func:`held_ends_basis` of ``n`` nodes, its arrays read-only (shared: the
    template of every copy, and the basis :mod:`.system_fd_build` recognises)."""
    inner = max(n - 2, 0)
    per_row = np.zeros(3 * n, dtype=np.int32)
    per_row[3 : 3 + 3 * inner] = 3
    indptr = np.concatenate(([0], np.cumsum(per_row))).astype(np.int32)
    indices = np.repeat(np.arange(3 * inner, dtype=np.int32).reshape(inner, 1, 3), 3, axis=1)
    data = np.tile(np.eye(3).ravel(), inner)
    for a in (data, indices, indptr):
        a.flags.writeable = False
    return sp.csr_matrix((data, indices.ravel(), indptr), shape=(3 * n, 3 * inner))
