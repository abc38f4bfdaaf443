"""The dynamic analysis of a case by its method: ``time`` (:mod:`cablestudy.analyses.time`),
``frequency`` (:mod:`cablestudy.analyses.frequency`), ``auto`` (the frequency domain where
it is trusted, else the time domain); what each method cannot model, refused before any
work; and the frequency-domain cases of a chunk solved together per linear model.
"""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np

from ..statics import (
    STATUS_OK,
    StaticResult,
)
from ..study.analysis import (
    DynamicSettings,
    HarmonicExcitation,
    SpectrumExcitation,
)
from ..study.cases import Case
from ..study.ends import ForceEnd, MooringEnd
from ..study.loader import StudySource
from .common import CheckedOutputs
from .static import solve_static
from .time import dynamic_outputs, solve_dynamic


def linear_model_gaps(study: Any) -> list[tuple[tuple[str | int, ...], str]]:
    """Keys of ``study`` set to something the frequency-domain solver cannot represent,
    as (YAML path, what it is): a line that parts, a winch, a catenary line sliding over
    pulleys, which the time domain models."""
    gaps: list[tuple[tuple[str | int, ...], str]] = []
    if study.line.kind == "spring":
        return gaps
    # the linearised line cannot part or change its length
    if study.line.failure is not None:
        gaps.append((("line", "failure"), "a break condition (the line parts)"))
    gaps += [
        (("line", "segments", i, "failure"), "a break condition (the line parts)")
        for i, seg in enumerate(study.line.segments)
        if seg.failure is not None
    ]
    if study.line.winch is not None:
        gaps.append((("line", "winch"), "a winch (the line's length changes)"))
    if study.line.pulleys:
        gaps.append((("line", "pulleys"), "a line sliding over pulleys"))
    return gaps


def linear_model_problems(cases: list[Case], src: StudySource) -> list[str]:
    """Keys that ``method: frequency`` would ignore, refused naming the method that
    models them (``method: auto`` runs such cases in the time domain)."""
    problems: list[str] = []
    for case in cases:
        study = case.study
        dyn = study.analysis.dynamic
        if dyn is not None and dyn.method == "frequency" and not study.is_system:
            for path, what in linear_model_gaps(study):
                loc = ".".join(str(p) for p in path)
                problems.append(
                    f"{src.line_of(path) or src.line_of(path[:1])}: {loc}: {what} is modelled "
                    "by the time domain, not by analysis.dynamic.method: frequency; allowed: "
                    "method time or auto, or remove the key"
                )
        if len(problems) > 20:
            break
    return problems


def dynamic_problems(cases: list[Case], src: StudySource) -> list[str]:
    """Config errors of the dynamic analysis that need the whole study (ends, length)."""
    problems: list[str] = []
    for case in cases:
        dyn = case.study.analysis.dynamic
        if dyn is None or case.study.is_system:  # a system's: study.system_dynamics
            continue
        study = case.study
        excited = {e.end for e in dyn.excitations}
        for label in ("a", "b"):
            end = getattr(study.ends, label)
            # a 'force' or 'mooring' end fixes the static equilibrium; an end the
            # excitation moves then moves about that static position (a vessel-attached
            # end). An unexcited 'force' end is a free node carrying its force (a towed
            # body); an unexcited 'mooring' end (a constant horizontal force at a held
            # height) is no physical support: refused, saying what to write instead.
            if isinstance(end, MooringEnd) and label not in excited:
                line = src.line_of(("ends", label, "kind"))
                problems.append(
                    f"{line}: ends.{label}.kind: 'mooring' is not supported with "
                    "analysis.dynamic unless the excitation moves this end: a fairlead held at "
                    "a height with a constant horizontal force is no support the line can move "
                    "against; allowed: an excitation with end: "
                    f"{label} (the vessel's motion), kind 'fixed' at the static position "
                    "(force_b in a statics run gives it), or kind 'force' for a free end"
                )
            if isinstance(end, ForceEnd) and label not in excited and dyn.method == "frequency":
                line = src.line_of(("ends", label, "kind"))
                problems.append(
                    f"{line}: ends.{label}.kind: an unexcited 'force' end is a free end, "
                    "modelled by the time domain only; allowed: analysis.dynamic.method: time "
                    "or auto"
                )
        if dyn.transfer_function is not None and "frequency" in case.coords:
            line = src.line_of(("analysis", "dynamic", "transfer_function"))
            problems.append(
                f"{line}: analysis.dynamic.transfer_function: writes its own 'frequency' "
                "dimension, and the sweep has an axis named 'frequency'; allowed: a "
                "transfer function instead of the frequency sweep, or name the sweep axis "
                "otherwise (name: ...)"
            )
        spectral = any(isinstance(e, SpectrumExcitation) for e in dyn.excitations)
        if spectral and dyn.method == "frequency" and "frequency" in case.coords:
            line = src.line_of(("analysis", "dynamic", "excitation"))
            problems.append(
                f"{line}: analysis.dynamic.excitation: a spectrum's tension spectrum is "
                "written on a 'frequency' dimension, and the sweep has an axis named "
                "'frequency'; allowed: name the sweep axis otherwise (name: ...)"
            )
        length = study.line.total_length
        if dyn.history is not None:
            for i, s in enumerate(dyn.history.points):
                if s > length:
                    line = src.line_of(("analysis", "dynamic", "history", "points", i))
                    problems.append(
                        f"{line}: analysis.dynamic.history.points.{i}: s = {s} lies beyond "
                        f"the end of the line; allowed 0 <= s <= {length}"
                    )
        if dyn.duration is None and dyn.max_periods < math.ceil(dyn.ramp_periods) + dyn.min_periods:
            line = src.line_of(("analysis", "dynamic", "max_periods"))
            problems.append(
                f"{line}: analysis.dynamic.max_periods: {dyn.max_periods} leaves no room for "
                f"the ramp ({dyn.ramp_periods} periods) and min_periods ({dyn.min_periods}); "
                f"allowed >= {math.ceil(dyn.ramp_periods) + dyn.min_periods}"
            )
        if len(problems) > 20:
            break
    return problems


def auto_ineligible(dyn: DynamicSettings, study: Any = None) -> str:
    """Why ``method: auto`` cannot try the frequency domain for these settings ("" if it
    can): it needs one harmonic frequency, time histories come from the time domain, and
    so do free ends and what the linearised model lacks (:func:`linear_model_gaps`)."""
    if study is not None:
        excited = {e.end for e in dyn.excitations}
        for label in ("a", "b"):
            if isinstance(getattr(study.ends, label), ForceEnd) and label not in excited:
                return f"end {label} is free (time domain only)"
        gaps = linear_model_gaps(study)
        if gaps:
            return f"{gaps[0][1]} (time domain only)"
    if not all(isinstance(e, HarmonicExcitation) for e in dyn.excitations):
        return "excitation is not harmonic"
    if len({e.frequency for e in dyn.excitations}) > 1:  # type: ignore[union-attr]
        return "excitation has several frequencies"
    if dyn.history is not None:
        return "time histories asked for"
    if dyn.duration is not None:
        return "a fixed run duration asked for"
    return ""


def run_dynamic(
    case: Case, static: StaticResult, deadline: float | None, outcome: Any = None
) -> tuple[int, str, dict[str, np.ndarray]]:
    """The case's dynamic analysis by its method: (status, message, outputs).

    ``time``: the time domain; ``frequency``: the linearised harmonic response;
    ``auto``: the frequency domain where :mod:`cablestudy.analyses.frequency` trusts it,
    else the time domain. ``dynamic_method`` and ``dynamic_method_reason`` record
    which ran and why. ``outcome``: the case's frequency-domain outcome when already
    solved (with the other cases of its chunk, :func:`evaluate_chunk`)."""
    dyn = case.study.analysis.dynamic
    assert dyn is not None
    if case.study.line.is_spring:
        from .spring import run_spring_dynamic

        return run_spring_dynamic(case, static, deadline)
    linear: dict[str, np.ndarray] = {}
    if dyn.method in ("frequency", "auto"):
        why = auto_ineligible(dyn, case.study) if dyn.method == "auto" else ""
        if not why:
            if outcome is not None:
                fres = outcome
            else:
                from .frequency import solve_frequency

                fres = solve_frequency(case, static, deadline)
            if dyn.method == "frequency" or (fres.status == STATUS_OK and not fres.distrust):
                out = dict(fres.data) if fres.non_finite is None else CheckedOutputs(fres.data)
                if fres.non_finite is not None:
                    out.non_finite = fres.non_finite  # type: ignore[attr-defined]
                out["dynamic_method"] = np.asarray("frequency")
                out["dynamic_method_reason"] = (
                    np.asarray("method: frequency")
                    if dyn.method == "frequency"
                    else np.asarray(f"auto: linear ({fres.summary})")
                )
                return fres.status, fres.message, out
            from .frequency import TRANSFER_OUTPUTS

            why = fres.distrust or fres.message
            # the transfer function is a linear result whichever method answers the case
            linear = {k: v for k, v in fres.data.items() if k in TRANSFER_OUTPUTS}
        elif dyn.transfer_function is not None:
            # auto runs the time domain for this case; the transfer function asked for
            # is still the linear model's
            from .frequency import TRANSFER_OUTPUTS, solve_frequency

            fres = solve_frequency(case, static, deadline)
            linear = {k: v for k, v in fres.data.items() if k in TRANSFER_OUTPUTS}
        reason = f"auto: {why}"
    else:
        reason = "method: time"
    dres = solve_dynamic(case, static, deadline)
    out = dynamic_outputs(dres, dyn, static.s)
    line_def = case.study.line
    if line_def.failure is not None or any(seg.failure for seg in line_def.segments):
        out["break_time"] = np.asarray(dres.break_time)
        out["break_s"] = np.asarray(dres.break_s)
    if case.study.line.winch is not None:
        out["winch_paid_out"] = np.asarray(dres.winch_paid_out)
    out["dynamic_method_reason"] = np.asarray(reason)
    out.update(linear)
    message = dres.message
    if dres.status != STATUS_OK and dyn.method == "auto":
        message = f"{reason}, so the time domain ran: {dres.message}"
    return dres.status, message, out


def presolve_frequency(
    cases: list[Case], presolved: dict[str, StaticResult]
) -> tuple[dict[int, Any], dict[int, float]]:
    """The frequency-domain outcomes of the cases that will ask for one (``method:
    frequency``, or ``auto`` where the frequency domain may answer), solved together
    per shared linear model (:func:`cablestudy.analyses.frequency.solve_frequency_cases`):
    by position in ``cases``, with each case's share of its group's wall time [s].
    Anything unexpected leaves the cases to the one-by-one path (which records its own
    errors), as does a group whose statics or linear model fail. A chunk without such a
    case loads nothing of the frequency domain."""
    asking = []
    for i, case in enumerate(cases):
        dyn = case.study.analysis.dynamic
        if dyn is None or dyn.method == "time":
            continue
        if dyn.method == "auto" and auto_ineligible(dyn, case.study):
            continue
        asking.append(i)
    if not asking:
        return {}, {}
    from .frequency import batch_key, linearised, solve_frequency_cases

    groups: dict[tuple, list[int]] = {}
    for i in asking:
        key = batch_key(cases[i])
        if key is not None:
            groups.setdefault(key, []).append(i)
    outcomes: dict[int, Any] = {}
    share: dict[int, float] = {}
    for members in groups.values():
        t0 = time.perf_counter()
        first = cases[members[0]]
        try:
            deadline = time.monotonic() + first.study.analysis.time_limit
            static = solve_static(first, deadline, presolved)
            if not static.success:
                continue
            red, _ = linearised(first, static, deadline)
            if red is None:
                continue
            solved = solve_frequency_cases([cases[i] for i in members], static, red)
        except Exception:  # noqa: BLE001 - the per-case path reports it
            continue
        each = (time.perf_counter() - t0) / len(members)
        for i, outcome in zip(members, solved, strict=True):
            outcomes[i] = outcome
            share[i] = each
    return outcomes, share
