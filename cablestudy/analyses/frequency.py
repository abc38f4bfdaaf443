"""Case-level glue of the frequency-domain method and of ``method: auto``.

A sweep over excitation frequency and amplitude shares one static problem: the
linearised line (:func:`cablestudy.dynamics.linear_model.linear_line`, projected on
its free degrees of freedom) is built once per (static hash, elements) and cached in
the process, like the static solutions of :mod:`cablestudy.analyses`; per case only
the drag iteration and the complex solves run. :data:`COUNTERS` counts the static
solves and linear-model assemblies of this process (reported by the sweep benchmark
and checked by a test).
"""

from __future__ import annotations

import contextlib
import math
import struct
from collections import OrderedDict
from dataclasses import dataclass

import numpy as np

from ..dynamics.frequency import solve_harmonic, solve_spectrum
from ..dynamics.frequency_model import STATUS_NOT_CONVERGED, DragSettings, ReducedLine
from ..dynamics.linear_model import linear_line
from ..dynamics.modal import ModalProblem
from ..dynamics.system_validity import line_failures
from ..dynamics.touchdown_mesh import TOUCHDOWN_SAMPLES, touchdown_mesh
from ..dynamics.validity import Validity
from ..statics import STATUS_NO_SOLUTION, STATUS_NUMERICAL, STATUS_OK, StaticResult
from ..statics.base import StaticProblem
from ..study.analysis import AutoSettings, DynamicSettings, HarmonicExcitation, SpectrumExcitation
from ..study.cases import Case
from ..study.problem import static_problem
from .along_line import tension_along
from .counters import COUNTERS, trim_lru
from .line_harmonic import line_harmonic, submerged_weight, z_envelope

#: outputs of the transfer function (analysis.dynamic.transfer_function)
TRANSFER_OUTPUTS = (
    "transfer_frequency",
    "tension_rao_a",
    "tension_rao_b",
    "tension_rao_phase_a",
    "tension_rao_phase_b",
    "tension_rao_line",
)

_LINEAR_CACHE: OrderedDict[tuple[str, int], tuple[ReducedLine | None, str]] = OrderedDict()
_LINEAR_CACHE_SIZE = 64
#: the static problem of the last static hash (the cases of a frequency sweep share it)
_LAST_PROBLEM: dict[str, StaticProblem] = {}


def _problem(case: Case) -> StaticProblem:
    """:func:`cablestudy.study.problem.static_problem` of the case's study, built once for the
    cases that share its static hash (every input of the static problem is in it)."""
    hit = _LAST_PROBLEM.get(case.static_hash)
    if hit is None:
        hit = static_problem(case.study)
        _LAST_PROBLEM.clear()
        _LAST_PROBLEM[case.static_hash] = hit
    return hit


def linearised(
    case: Case, static: StaticResult, deadline: float | None
) -> tuple[ReducedLine | None, str]:
    """The case's line linearised about its static shape at ``elements + 1`` equally
    spaced nodes (cached per static problem); or None and why not."""
    from .line_model import dynamic_extras
    from .static import static_at

    dyn = case.study.analysis.dynamic
    assert dyn is not None
    key = (case.static_hash, dyn.elements)
    cached = _LINEAR_CACHE.get(key)
    if cached is not None:
        with contextlib.suppress(KeyError):  # evicted by another thread
            _LINEAR_CACHE.move_to_end(key)
        return cached
    n_nodes = dyn.elements + 1
    mesh = static if len(static.s) == n_nodes else static_at(case, n_nodes, deadline)
    if mesh.success and static.laid_length > 0.0:
        mesh = _with_touchdown_nodes(case, dyn.elements, deadline) or mesh
    out: tuple[ReducedLine | None, str]
    if not mesh.success:
        out = (None, f"static shape at the dynamic nodes: {mesh.message}")
    else:
        T_e = 0.5 * (mesh.tension[:-1] + mesh.tension[1:])
        # a stretch laid on the seabed that friction has emptied of tension is held by
        # the seabed, not a slack span: only a suspended element must be taut
        med = _problem(case).medium
        ground = med.seabed_z(mesh.position[:, 0], mesh.position[:, 1])
        on_bed = mesh.position[:, 2] - ground <= 1e-6 * max(float(mesh.s[-1]), 1.0)
        slack = (T_e <= 0.0) & ~(on_bed[:-1] & on_bed[1:])
        if np.any(slack):
            i = int(np.flatnonzero(slack)[np.argmin(T_e[slack])])
            out = (
                None,
                f"the static line is slack near s = {0.5 * (mesh.s[i] + mesh.s[i + 1]):.6g} m "
                f"(element tension {T_e[i]:.4g} N); the frequency domain needs a taut line",
            )
        else:
            problem = static_problem(case.study)
            line = linear_line(
                ModalProblem(
                    line=problem.line,
                    medium=problem.medium,
                    end_a=problem.end_a,
                    end_b=problem.end_b,
                    static=mesh,
                    extras=dynamic_extras(case.study, mesh.position),
                )
            )
            COUNTERS["linear_assemblies"] += 1
            out = (ReducedLine.of(line), "")
    _LINEAR_CACHE[key] = out
    trim_lru(_LINEAR_CACHE, _LINEAR_CACHE_SIZE)
    return out


def _with_touchdown_nodes(case: Case, elements: int, deadline: float | None) -> StaticResult | None:
    """The uniform nodes plus a node at each touchdown point
    (:func:`cablestudy.dynamics.touchdown_mesh.touchdown_mesh`, shared with the lines
    of a system); None if the fine sampling fails."""
    from .static import static_at

    fine = static_at(case, elements * TOUCHDOWN_SAMPLES + 1, deadline)
    if not fine.success:
        return None
    return touchdown_mesh(fine, static_problem(case.study).medium, elements)


def end_displacements(dyn: DynamicSettings) -> tuple[np.ndarray, float, complex]:
    """Complex end displacements [m] (2, 3) of ``Re(X e^{i w t})``, the excitation
    frequency [Hz], and the complex phase factor of the first excitation (the
    reference of the tension phases). ``a sin(w t + phi) d`` is ``Re(-i a e^{i phi}
    d e^{i w t})``."""
    harmonics = [e for e in dyn.excitations if isinstance(e, HarmonicExcitation)]
    # the cases of a sweep over frequency share their motions: computed once per
    # distinct (end, amplitude, phase, direction) list, keyed by the exact floats
    key = tuple((e.end, _FLOATS(e.amplitude, e.phase_deg, *e.direction)) for e in harmonics)
    hit = _MOTIONS.get(key)
    if hit is None:
        hit = _end_displacements(harmonics)
        if len(_MOTIONS) >= _MOTIONS_SIZE:
            _MOTIONS.clear()
        _MOTIONS[key] = hit
    return hit[0].copy(), harmonics[0].frequency, hit[1]


#: :func:`_end_displacements` by excitation (see :func:`end_displacements`)
_MOTIONS: dict[tuple, tuple[np.ndarray, complex]] = {}
_MOTIONS_SIZE = 256
#: the bytes of five floats (a key that tells -0.0 from 0.0)
_FLOATS = struct.Struct("<5d").pack


def _end_displacements(harmonics: list[HarmonicExcitation]) -> tuple[np.ndarray, complex]:
    X = np.zeros((2, 3), dtype=complex)
    for e in harmonics:
        d = np.asarray(e.direction, dtype=float)
        X[0 if e.end == "a" else 1] += (
            -1j * e.amplitude * np.exp(1j * math.radians(e.phase_deg)) * (d / np.linalg.norm(d))
        )
    first = harmonics[0]
    return X, -1j * np.exp(1j * math.radians(first.phase_deg))


#: the drag settings of a study that sets none (frozen: one object serves every case)
_DEFAULT_DRAG = DragSettings()


def drag_settings(dyn: DynamicSettings) -> DragSettings:
    lin = dyn.linearisation
    if lin is None:
        return _DEFAULT_DRAG
    return DragSettings(
        tolerance=lin.tolerance,
        max_iterations=lin.max_iterations,
        samples=DragSettings.samples if lin.samples is None else lin.samples,
        exact=lin.samples is None,
    )


@dataclass(kw_only=True)
class FrequencyOutcome:
    status: int
    message: str
    data: dict[str, np.ndarray]
    distrust: str = ""  # why method auto would not trust it ("" if it would)
    validity: Validity | None = None
    drag_converged: bool = True
    #: the float outputs in ``data`` holding NaN or infinity (sorted names, as
    #: :func:`cablestudy.analyses.common.non_finite_outputs` finds them), when already known
    non_finite: list[str] | None = None

    @property
    def summary(self) -> str:
        """The validity measures in words ("" without them)."""
        v = self.validity
        if v is None:
            return ""
        return (
            f"min/static tension {v.min_tension_ratio:.3g}, "
            f"amplitude/sag {v.amplitude_sag_ratio:.3g}"
        )


def solve_frequency(case: Case, static: StaticResult, deadline: float | None) -> FrequencyOutcome:
    """The harmonic response of the case, its outputs, and the auto checks (as one case
    of :func:`solve_frequency_cases`, so a case gives the same record alone or in a
    chunk)."""
    dyn = case.study.analysis.dynamic
    assert dyn is not None
    red, why = linearised(case, static, deadline)
    if red is None:
        return FrequencyOutcome(status=STATUS_NO_SOLUTION, message=why, data={}, distrust=why)
    spectra = [e for e in dyn.excitations if isinstance(e, SpectrumExcitation)]
    if spectra:
        return irregular(red, spectra[0], dyn, static, _problem(case))
    return solve_frequency_cases([case], static, red)[0]


def batch_key(case: Case) -> tuple | None:
    """What the cases of one :func:`solve_frequency_cases` call share (static problem,
    dynamic nodes, drag settings); None for a case that call does not take (no
    dynamics, a spectrum, a spring line)."""
    dyn = case.study.analysis.dynamic
    if dyn is None or case.study.line.is_spring:
        return None
    if not all(isinstance(e, HarmonicExcitation) for e in dyn.excitations):
        return None
    return (case.static_hash, dyn.elements, drag_settings(dyn))


#: most (cases x nodes) solved in one call: its arrays (displacements, tensions) stay
#: under about 100 MB however long the line and large the chunk
BATCH_NODES = 1_000_000


def solve_frequency_cases(
    cases: list[Case], static: StaticResult, red: ReducedLine
) -> list[FrequencyOutcome]:
    """:func:`solve_frequency` for harmonic cases that share a linearised line ``red``
    and its static solution ``static`` (the same :func:`batch_key`): one compiled call
    solves them all (:func:`cablestudy.dynamics.harmonic_cases.solve_harmonic_cases`),
    and their outputs and validity measures are computed as arrays (in slices of at
    most :data:`BATCH_NODES` case-nodes)."""
    step = max(1, BATCH_NODES // red.line.n_nodes)
    if len(cases) > step:
        return [
            outcome
            for i in range(0, len(cases), step)
            for outcome in solve_frequency_cases(cases[i : i + step], static, red)
        ]
    K = len(cases)
    dyns = [c.study.analysis.dynamic for c in cases]
    omegas = np.empty(K)
    motion = np.empty((K, 2, 3), dtype=complex)
    refs = np.empty(K, dtype=complex)
    for k, dyn in enumerate(dyns):
        assert dyn is not None
        X, freq, ref = end_displacements(dyn)
        omegas[k] = 2.0 * math.pi * freq
        motion[k] = X
        refs[k] = ref
    assert dyns[0] is not None
    problem = _problem(cases[0])
    # the solve and the arrays of the outputs (shared with a system of one line)
    got = line_harmonic(
        red, omegas, motion, drag_settings(dyns[0]), static, problem.medium, problem.line
    )
    res, a_end = got.res, got.amplitude
    t_end = res.tension_static
    phase = np.degrees(np.angle(res.end_tension / refs[:, None]))
    edge_max = np.max(t_end[None] + a_end, axis=1)
    ratio, sag_ratio, travel = got.ratio, got.sag_ratio, got.travel
    med = problem.medium
    # the outputs of every case as arrays (K, ...); a case's own are views of them
    ex = np.array([0 if dyn.excitations[0].end == "a" else 1 for dyn in dyns])  # type: ignore[union-attr]
    t_ex = t_end[ex]
    a_ex = a_end[np.arange(K), ex]
    env_max = got.envelope_max
    top = np.max(env_max, axis=1)
    columns: dict[str, np.ndarray] = {
        "tension_static": t_ex,
        "tension_max": t_ex + a_ex,
        "tension_min": t_ex - a_ex,
        "tension_mean": t_ex,
        # max(line, ends) as Python's max: the second only where larger
        "tension_max_line": np.where(edge_max > top, edge_max, top),
        "tension_envelope_max": env_max,
        "tension_envelope_min": got.envelope_min,
        "z_envelope_max": got.z_max,
        "tension_amplitude_a": a_end[:, 0],
        "tension_amplitude_b": a_end[:, 1],
        "tension_phase_a": phase[:, 0],
        "tension_phase_b": phase[:, 1],
        "steady_converged": np.ones(K, dtype=np.asarray(1).dtype),
        "linearisation_iterations": res.iterations.astype(np.asarray(1).dtype),
        "linearisation_converged": res.converged.astype(np.asarray(1).dtype),
    }
    if med.depth is not None:  # a seabed to touch, as the time domain's (touchdown_range)
        columns["touchdown_min"] = got.touchdown_min
        columns["touchdown_max"] = got.touchdown_max
    from .common import non_finite_cases

    bad = non_finite_cases(columns, "dynamic")
    items = list(columns.items())
    ratio_l, sag_l, travel_l = ratio.tolist(), sag_ratio.tolist(), travel.tolist()
    iterations_l, converged_l = res.iterations.tolist(), res.converged.tolist()
    out = []
    for k, dyn in enumerate(dyns):
        assert dyn is not None
        if not res.ok[k]:
            why = f"singular dynamic matrix at {omegas[k] / (2 * math.pi):.6g} Hz"
            out.append(
                FrequencyOutcome(status=STATUS_NUMERICAL, message=why, data={}, distrust=why)
            )
            continue
        data: dict[str, np.ndarray] = {name: col[k, ...] for name, col in items}
        known: list[str] | None = bad[k]
        if dyn.transfer_function is not None:
            data.update(transfer_function(red, dyn, static))
            known = None
        v = Validity(
            min_tension_ratio=ratio_l[k],
            amplitude_sag_ratio=sag_l[k],
            touchdown_travel=travel_l[k],
        )
        outcome = _judged(data, v, dyn, converged_l[k], iterations_l[k], res.change[k])
        outcome.non_finite = known
        out.append(outcome)
    return out


#: the checks of ``method: auto`` when a study sets none (built once: a model per case
#: costs more than the checks)
_DEFAULT_AUTO = AutoSettings()


def _judged(
    data: dict[str, np.ndarray],
    v: Validity,
    dyn: DynamicSettings,
    converged: bool,
    iterations: int,
    change: float,
) -> FrequencyOutcome:
    """A solved case's outcome with the checks of ``method: auto`` on its measures."""
    auto = dyn.auto or _DEFAULT_AUTO
    if not converged:  # the transfer function asked for is its own linear solve: kept
        failed = unsettled_fit(dyn, iterations, change)
        failed.data.update((k, x) for k, x in data.items() if k in TRANSFER_OUTPUTS)
        return failed
    reasons = line_failures(v, auto)
    return FrequencyOutcome(
        status=STATUS_OK,
        message="",
        data=data,
        distrust="; ".join(reasons),
        validity=v,
        drag_converged=converged,
    )


def unsettled_fit(dyn: DynamicSettings, iterations: int, change: float) -> FrequencyOutcome:
    """The outcome of a frequency-domain case whose drag linearisation stopped at
    ``analysis.dynamic.linearisation.max_iterations`` without settling: not verified,
    so failed (status 7, its message, no dynamic outputs), as a system's case is
    (:mod:`cablestudy.dynamics.system_frequency`); ``method: auto`` runs the time
    domain instead."""
    settings = drag_settings(dyn)
    why = (
        f"drag linearisation did not converge in {iterations} iterations "
        f"(last change {change:.3g}, tolerance {settings.tolerance:.3g})"
    )
    return FrequencyOutcome(
        status=STATUS_NOT_CONVERGED, message=why, data={}, distrust=why, drag_converged=False
    )


def transfer_function(
    red: ReducedLine, dyn: DynamicSettings, static: StaticResult
) -> dict[str, np.ndarray]:
    """Tension per unit excitation amplitude [N/m] at the transfer-function frequencies:
    the excitation of the case (directions, phases, amplitude ratios) at each frequency,
    drag linearised at the case's amplitude, divided by the largest amplitude. NaN at a
    frequency whose dynamic matrix is singular or whose drag linearisation does not
    settle (:func:`cablestudy.analyses.plausibility.dynamic_warnings` warns of them)."""
    assert dyn.transfer_function is not None
    freqs = np.asarray(dyn.transfer_function.values)
    X, scale, ref = rao_motion(dyn)
    settings = drag_settings(dyn)
    n_out = static.s.size
    end_amp = np.full((freqs.size, 2), np.nan)
    end_phase = np.full((freqs.size, 2), np.nan)
    line_amp = np.full((freqs.size, n_out), np.nan)
    for k, f in enumerate(freqs):
        res = solve_harmonic(red, 2.0 * math.pi * f, X, settings)
        if not res.success or not res.drag_converged:  # NaN there, and a warning
            continue
        end_amp[k] = np.abs(res.end_tension) / scale
        end_phase[k] = np.degrees(np.angle(res.end_tension / ref))
        line_amp[k] = (
            tension_along(
                static.s, red.line.s, np.abs(res.element_tension), np.abs(res.end_tension)
            )
            / scale
        )
    return {
        "transfer_frequency": freqs,
        "tension_rao_a": end_amp[:, 0],
        "tension_rao_b": end_amp[:, 1],
        "tension_rao_phase_a": end_phase[:, 0],
        "tension_rao_phase_b": end_phase[:, 1],
        "tension_rao_line": line_amp,
    }


def rao_motion(dyn: DynamicSettings) -> tuple[np.ndarray, float, complex]:
    """The end displacements [m] (2, 3) the transfer function is solved for, the
    amplitude [m] its tensions are divided by, and the phase reference (as
    :func:`end_displacements`). The amplitude is the largest excitation's ``amplitude``
    (the length of its motion along its unit direction; a component of a direction off
    the axes is shorter). With every amplitude 0 the small-motion limit is meant: each
    motion at 1e-9 m (the drag linearised at rest), divided by that."""
    X, _, ref = end_displacements(dyn)
    amplitude = max(e.amplitude for e in dyn.excitations if isinstance(e, HarmonicExcitation))
    if amplitude > 0.0:
        return X, float(amplitude), ref
    tiny = 1e-9
    harmonics = [e for e in dyn.excitations if isinstance(e, HarmonicExcitation)]
    X, ref = _end_displacements([e.model_copy(update={"amplitude": tiny}) for e in harmonics])
    return X, tiny, ref


def irregular(
    red: ReducedLine,
    spec: SpectrumExcitation,
    dyn: DynamicSettings,
    static: StaticResult,
    problem: StaticProblem,
) -> FrequencyOutcome:
    """Response to an end-motion spectrum: tension standard deviations, spectra and the
    most probable maxima over ``storm_duration``. With the tension a narrow-band
    Gaussian process its peaks are Rayleigh-distributed, and the most probable largest
    of ``N = duration / T_z`` of them is ``sigma sqrt(2 ln N)`` above the mean, with the
    zero up-crossing period ``T_z = 2 pi sqrt(m0 / m2)`` from the tension spectrum's
    moments ``m_j = sum_k w_k^j |dT_k|^2 / 2``.

    On a seabed (``problem``'s medium) the touchdown point's range over the storm, as the
    time domain's over its run: the travel estimate of the harmonic case
    (:func:`cablestudy.analyses.touchdown_range.touchdown_range`) is linear in the
    tension variation of the element at the touchdown point, so its most probable
    maximum over the storm is the estimate at that element's most probable maximum
    tension variation (the same statistic as ``tension_max``)."""
    freqs = np.asarray(spec.line_frequencies)
    amps = np.asarray(spec.line_amplitudes)
    d = np.asarray(spec.direction, dtype=float)
    X = np.zeros((freqs.size, 2, 3), dtype=complex)
    X[:, 0 if spec.end == "a" else 1] = amps[:, None] * (d / np.linalg.norm(d))[None]
    omegas = 2.0 * math.pi * freqs
    res = solve_spectrum(red, omegas, X, drag_settings(dyn))
    if res.status != STATUS_OK:
        return FrequencyOutcome(
            status=res.status, message=res.message, data={}, distrust=res.message
        )
    df = float(freqs[1] - freqs[0])

    def mpm(power: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(standard deviation, most probable maximum amplitude) of line powers
        |dT_k|^2 (K, ...)."""
        m0 = 0.5 * np.sum(power, axis=0)
        m2 = 0.5 * np.sum(omegas.reshape((-1,) + (1,) * (power.ndim - 1)) ** 2 * power, axis=0)
        tz = 2.0 * math.pi * np.sqrt(m0 / np.where(m2 > 0.0, m2, np.inf))
        n_peaks = np.maximum(spec.storm_duration / np.where(tz > 0.0, tz, np.inf), 1.0)
        return np.sqrt(m0), np.sqrt(m0) * np.sqrt(2.0 * np.log(n_peaks))

    sd_end, mpm_end = mpm(np.abs(res.end_tension) ** 2)
    _, mpm_el = mpm(np.abs(res.element_tension) ** 2)
    _, mpm_z = mpm(np.abs(res.displacement[..., 2]) ** 2)
    _, mpm_xyz = mpm(np.abs(res.displacement) ** 2)
    ex = 0 if spec.end == "a" else 1
    t_end = res.tension_static
    env = tension_along(static.s, red.line.s, mpm_el, mpm_end)
    data: dict[str, np.ndarray] = {
        "tension_static": np.asarray(t_end[ex]),
        "tension_max": np.asarray(t_end[ex] + mpm_end[ex]),
        "tension_min": np.asarray(t_end[ex] - mpm_end[ex]),
        "tension_mean": np.asarray(t_end[ex]),
        "tension_max_line": np.asarray(
            max(float(np.max(static.tension + env)), float(np.max(t_end + mpm_end)))
        ),
        "tension_envelope_max": static.tension + env,
        "tension_envelope_min": static.tension - env,
        "z_envelope_max": z_envelope(static.s, red.line, mpm_z),
        "tension_std_a": np.asarray(sd_end[0]),
        "tension_std_b": np.asarray(sd_end[1]),
        "transfer_frequency": freqs,
        "tension_psd_a": np.abs(res.end_tension[:, 0]) ** 2 / (2.0 * df),
        "tension_psd_b": np.abs(res.end_tension[:, 1]) ** 2 / (2.0 * df),
        "linearisation_iterations": np.asarray(res.iterations),
        "linearisation_converged": np.asarray(int(res.converged)),
        # a statistical answer has no transient: steady, as a harmonic one (results guide)
        "steady_converged": np.asarray(1),
    }
    if problem.medium.depth is not None:  # a seabed to touch (as the harmonic cases)
        data.update(_touchdown_of_spectrum(red, static, problem, mpm_el, mpm_end, mpm_xyz))
    if not res.converged:
        return unsettled_fit(dyn, res.iterations, res.change)
    return FrequencyOutcome(status=STATUS_OK, message="", data=data, distrust="")


def _touchdown_of_spectrum(
    red: ReducedLine,
    static: StaticResult,
    problem: StaticProblem,
    mpm_el: np.ndarray,
    mpm_end: np.ndarray,
    mpm_xyz: np.ndarray,
) -> dict[str, np.ndarray]:
    """``touchdown_min``, ``touchdown_max`` [m] of a spectrum's response (see
    :func:`irregular`): the travel measure of ``method: auto``
    (:func:`cablestudy.dynamics.validity.measures_cases`) at the most probable maxima of
    the element and end tension variations ``mpm_el`` (n - 1,), ``mpm_end`` (2,) [N]
    and of the node displacements ``mpm_xyz`` (n, 3) [m], on the nodes the harmonic
    cases judge laid (:func:`cablestudy.analyses.line_harmonic.line_outputs`)."""
    from ..dynamics.validity import measures_cases
    from .touchdown_range import touchdown_range

    line = red.line
    ground = problem.medium.seabed_z(line.position[:, 0], line.position[:, 1])
    on_bed = np.abs(line.position[:, 2] - ground) <= 1e-6 * max(float(line.s[-1]), 1.0)
    _, _, travel = measures_cases(
        s=line.s,
        position=line.position,
        displacement=mpm_xyz[None].astype(complex),
        element_tension_static=line.tension,
        element_tension_amplitude=mpm_el[None],
        end_tension_static=np.linalg.norm(line.end_force, axis=1),
        end_tension_amplitude=mpm_end[None],
        laid_length=static.laid_length,
        on_seabed=on_bed,
        submerged_weight=submerged_weight(problem.line, line.s),
    )
    low, high = touchdown_range(line.s, on_bed, travel)
    return {"touchdown_min": low[0], "touchdown_max": high[0]}
