"""The harmonic responses of one linearised line and the arrays its outputs are made of,
shared by the one-line study (:func:`cablestudy.analyses.frequency.
solve_frequency_cases`) and a system of one line between prescribed points
(:mod:`cablestudy.analyses.system_one_line`), so that the two give the same numbers bit
for bit (issue 24): the same solve (:func:`~cablestudy.dynamics.harmonic_cases.
solve_harmonic_cases`) on the same linear line, and the same operations from its
displacements and tensions to the end amplitudes, the tension envelope on the static
output points, the elevation envelope and the validity measures of ``method: auto``.

Pure: arrays in, a :class:`LineHarmonic` out.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..dynamics.frequency_model import DragSettings, ReducedLine
from ..dynamics.harmonic_cases import HarmonicCases, solve_harmonic_cases
from ..dynamics.validity import measures_cases
from .along_line import tension_along_cases
from .touchdown_range import touchdown_range


@dataclass(frozen=True, eq=False)
class LineHarmonic:
    """K harmonic responses of one line (``res``) and, per case (rows), the arrays of
    its outputs: ``amplitude`` [N] (K, 2) of the end tensions at A and B;
    ``envelope_max``/``_min`` [N] (K, n_out) the static tension at the static output
    points plus and minus the amplitude of its variation; ``z_max`` [m] (K, n_out) the
    highest elevation; ``ratio``, ``sag_ratio``, ``travel`` (K,) the validity measures
    (:func:`~cablestudy.dynamics.validity.measures_cases`); ``touchdown_min``/``_max``
    [m] (K,) the range of the touchdown point (:func:`.touchdown_range.touchdown_range`)."""

    res: HarmonicCases
    amplitude: np.ndarray
    envelope_max: np.ndarray
    envelope_min: np.ndarray
    z_max: np.ndarray
    ratio: np.ndarray
    sag_ratio: np.ndarray
    travel: np.ndarray
    touchdown_min: np.ndarray
    touchdown_max: np.ndarray


def submerged_weight(line_model: Any, s: np.ndarray) -> np.ndarray:
    """Submerged weight per length [N/m] of the static line model ``line_model`` (its
    ``segment_ends``, ``weight``, ``length``) at arc lengths ``s``."""
    ends = line_model.segment_ends
    idx = np.clip(np.searchsorted(ends, s, side="right") - 1, 0, len(line_model.length) - 1)
    return line_model.weight[idx]


def line_harmonic(
    red: ReducedLine,
    omegas: np.ndarray,
    motion: np.ndarray,
    settings: DragSettings,
    static: Any,
    medium: Any,
    line_model: Any,
) -> LineHarmonic:
    """The harmonic responses of the line ``red`` at ``omegas`` [rad/s] (K,) to the end
    motions ``motion`` [m] (K, 2, 3) complex, and their outputs' arrays. ``static``: the
    line's static solution at the output points (``s``, ``tension``, ``laid_length``);
    ``medium``: its static problem's medium (the seabed); ``line_model``: its static
    line model (the submerged weight)."""
    res = solve_harmonic_cases(red, omegas, motion, settings)
    return line_outputs(red.line, res, static, medium, line_model)


def line_outputs(
    line: Any, res: HarmonicCases, static: Any, medium: Any, line_model: Any
) -> LineHarmonic:
    """The outputs' arrays of the harmonic responses ``res`` of the linear line
    ``line`` (:func:`line_harmonic`'s, each case's row from its own response only)."""
    t_end = res.tension_static
    a_end = np.abs(res.end_tension)
    a_el = np.abs(res.element_tension)
    ground = medium.seabed_z(line.position[:, 0], line.position[:, 1])
    on_bed = np.abs(line.position[:, 2] - ground) <= 1e-6 * max(float(line.s[-1]), 1.0)
    ratio, sag_ratio, travel = measures_cases(
        s=line.s,
        position=line.position,
        displacement=res.displacement,
        element_tension_static=line.tension,
        element_tension_amplitude=a_el,
        end_tension_static=t_end,
        end_tension_amplitude=a_end,
        laid_length=static.laid_length,
        on_seabed=on_bed,
        submerged_weight=submerged_weight(line_model, line.s),
        held=np.diff(line.free_basis.tocsr().indptr).reshape(-1, 3).sum(axis=1) == 0,
    )
    envelope = tension_along_cases(static.s, line.s, a_el, a_end)
    touchdown_min, touchdown_max = touchdown_range(line.s, on_bed, travel)
    return LineHarmonic(
        res=res,
        amplitude=a_end,
        envelope_max=static.tension + envelope,
        envelope_min=static.tension - envelope,
        # each node's static elevation plus its heave amplitude, onto the output points
        z_max=z_envelope(static.s, line, np.abs(res.displacement[..., 2])),
        ratio=ratio,
        sag_ratio=sag_ratio,
        travel=travel,
        touchdown_min=touchdown_min,
        touchdown_max=touchdown_max,
    )


def z_envelope(s_out: np.ndarray, line: Any, amplitude: np.ndarray) -> np.ndarray:
    """The highest elevation [m] at the output points ``s_out`` [m] of a linear
    response: the model's static node elevations ``line.position[:, 2]`` plus the nodes'
    vertical amplitudes ``amplitude`` [m] (..., n) (a harmonic's, or a spectrum's most
    probable maximum), interpolated as the time domain's node maxima are."""
    z = line.position[:, 2] + np.asarray(amplitude)
    if z.ndim == 1:
        return np.interp(s_out, line.s, z)
    return np.array([np.interp(s_out, line.s, zk) for zk in z])
