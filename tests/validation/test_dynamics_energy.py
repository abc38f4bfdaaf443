"""Energy balance of the undamped line: the work done on the line by the moving end
equals the change of its kinetic, strain and gravitational energy. With spectral
radius 1 generalised-alpha is the trapezoidal rule, second-order accurate, so the
balance holds to O(h^2): the error must fall about fourfold when the step is halved.
"""

from __future__ import annotations

import numpy as np

from cablestudy.dynamics.assembly import evaluate
from cablestudy.dynamics.discrete_line import DiscreteLine

from .dynamics_helpers import moustafa_study, run_direct


def energies(
    line: DiscreteLine, x: np.ndarray, v: np.ndarray, anchor: np.ndarray | None = None
) -> tuple[float, float, float]:
    """(kinetic, stored elastic, potential of the constant nodal forces) energy [J] of
    the discrete line; the stored energy is the axial strain energy plus the bending
    and seabed-spring energies, and the potential is ``-sum(force . x)``: the test's
    own measure, from the definitions of :mod:`cablestudy.dynamics.model` (the time
    step never computes an energy)."""
    if np.any(line.law_code != 0):
        raise ValueError("energies: the stored axial energy is written for T = EA strain")
    work = evaluate(line, x, v, anchor=anchor if anchor is not None else x)
    kinetic = 0.5 * float(np.einsum("ia,iab,ib->", v, work.M_d, v))
    eps = np.maximum(work.strain, 0.0)
    stored = 0.5 * float(np.sum(line.axial_stiffness * line.rest_length * eps**2))
    d = np.diff(x, axis=0)
    u = d / np.linalg.norm(d, axis=1, keepdims=True)
    if line.has_bending:
        stored += 0.5 * float(np.sum(line.bending[1:-1] * np.sum((u[1:] - u[:-1]) ** 2, 1)))
        for end, (e, node) in enumerate(((0, 0), (-1, -1))):
            if line.bending[node] > 0.0:
                r = u[e] - line.clamp_direction[end]
                stored += 0.5 * float(line.bending[node] * r @ r)
    if line.has_seabed:
        gap = x @ line.seabed_normal - line.seabed_offset
        stored += 0.5 * float(np.sum(line.seabed_stiffness * np.minimum(gap, 0.0) ** 2))
    potential = -float(np.sum(line.force * x))
    return kinetic, stored, potential


def _balance_error(points_per_period: int) -> tuple[float, float]:
    study = moustafa_study(
        fluid="vacuum",
        dynamic={
            "excitation": {
                "end": "b",
                "direction": [1.0, 0.0, 0.0],
                "amplitude": 0.02,
                "frequency": 0.8,
            },
            "elements": 20,
            "spectral_radius": 1.0,
            "ramp_periods": 1.0,
            "points_per_period": points_per_period,
            "duration": 4.0,
        },
    )
    res, line, _ = run_direct(study)
    assert res.success, res.message
    rec = res.record
    assert rec is not None
    assert np.all(rec["tension"] > 0.0)  # stays taut: no slack-taut events
    energy = np.array([sum(energies(line, x, v)) for x, v in zip(rec["x"], rec["v"], strict=True)])
    # power of the support on the line: minus the line's force on the support, times
    # the end's velocity (end B moves, A is fixed)
    power = -np.sum(rec["end_force"][:, 1] * rec["v"][:, -1], axis=1)
    t = rec["t"]
    work = np.concatenate(([0.0], np.cumsum(0.5 * (power[1:] + power[:-1]) * np.diff(t))))
    error = np.max(np.abs((energy - energy[0]) - work))
    return error, float(np.max(np.abs(work)))


def test_work_of_the_moving_end_equals_the_change_of_energy() -> None:
    coarse, scale = _balance_error(64)
    fine, _ = _balance_error(128)
    # the balance holds to a small fraction of the energy exchanged...
    assert fine < 1e-2 * scale
    # ...and is a discretisation error of order two: halving the step divides it by
    # ~4 (observed order between 1.5 and 2.5)
    order = np.log2(coarse / fine)
    assert 1.5 < order < 2.5, (coarse, fine, order)
