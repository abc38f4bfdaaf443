"""The adapter from today's line assembly to the frequency-domain solver's input.

:func:`linear_line` builds a :class:`~cablestudy.dynamics.frequency.LinearLine` from
the modal assembly (:func:`~cablestudy.dynamics.modal.mass_blocks`,
:func:`~cablestudy.dynamics.modal.stiffness_matrix`,
:func:`~cablestudy.dynamics.modal.node_bases`) about a static shape sampled at the
nodes. It is the only place that knows where those arrays come from: when the line
model is unified, only this function changes.

What it adds to the modal assembly, with the time-domain model's laws
(:mod:`cablestudy.dynamics.model`): the axial structural damping of the elements,
``c = zeta l0 sqrt(EA m)`` [N s] acting on the strain rate; the nodal drag
coefficients ``1/2 rho C_N d l`` and ``1/2 rho pi C_T d l`` over the node's tributary
length ``l``; the current at the nodes; the node tangents (the chord of the two
neighbouring nodes). Both end nodes are prescribed (held, or moved by the
excitation), as in the time domain; nodes resting on the seabed are held as in
:func:`~cablestudy.dynamics.modal.node_bases` (normal to the seabed always; in all
directions where the seabed has friction: for small motions static friction keeps
the laid line from sliding, i.e. seabed friction is linearised as sticking).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import scipy.sparse as sp

from ..physics.current import current_velocity
from ..statics.base import EndCondition
from .frequency import LinearLine
from .modal import ModalProblem, _segment_index, mass_blocks, node_bases, stiffness_matrix


def _bar_matrix(coefficient: np.ndarray, direction: np.ndarray) -> sp.csr_matrix:
    """Assembled ``coefficient_e t_e t_e^T`` acting on the element elongations
    (3n, 3n)."""
    n = coefficient.size + 1
    blocks = coefficient[:, None, None] * direction[:, :, None] * direction[:, None, :]
    ii, jj = np.meshgrid(np.arange(3), np.arange(3), indexing="ij")
    a, b = np.arange(n - 1), np.arange(1, n)
    rows, cols, vals = [], [], []
    for ni, nj, sign in ((a, a, 1.0), (b, b, 1.0), (a, b, -1.0), (b, a, -1.0)):
        rows.append((3 * ni[:, None, None] + ii).ravel())
        cols.append((3 * nj[:, None, None] + jj).ravel())
        vals.append((sign * blocks).ravel())
    return sp.csr_matrix(
        (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(3 * n, 3 * n)
    )


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
    ea = line.axial_stiffness[seg]
    c_axial = line.damping_ratio[seg] * l0 * np.sqrt(ea * line.mass[seg])

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

    bases = node_bases(prob)
    dims = np.array([b.shape[1] for b in bases])
    offsets = np.concatenate(([0], np.cumsum(dims)))
    rows, cols, vals = [], [], []
    for i, basis in enumerate(bases):
        k = basis.shape[1]
        if k == 0:
            continue
        r3, ck = np.meshgrid(np.arange(3), np.arange(k), indexing="ij")
        rows.append(3 * i + r3.ravel())
        cols.append(offsets[i] + ck.ravel())
        vals.append(basis.ravel())
    free = sp.csr_matrix(
        (
            np.concatenate(vals) if vals else np.zeros(0),
            (
                np.concatenate(rows) if rows else np.zeros(0, int),
                np.concatenate(cols) if cols else np.zeros(0, int),
            ),
        ),
        shape=(3 * n, int(offsets[-1])),
    )
    return LinearLine(
        s=s,
        position=pos,
        mass=mass_blocks(prob),
        stiffness=stiffness_matrix(prob),
        damping=_bar_matrix(c_axial / l0, t),
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
        free_basis=free,
    )
