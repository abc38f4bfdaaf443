"""An a-posteriori check of the time step of a time-domain run (a line's or a system's),
applied where the step is at risk: where, in the periods the outputs come from, a node
landed on or lifted off the seabed, or an element changed between slack and taut.

Why there. The generalised-alpha step (:mod:`.integrator`) damps what it does not
resolve. On a smooth response that is the unresolved axial (elastic-wave) modes, which
the motion does not excite: the extremes then converge as the step squared and are
resolved at a few tens of steps a period. A landing or a lift-off, or a snap from slack
to taut, is a kick that rings the line's axial modes (a period of a fraction of a
second on a chain); a step too coarse to follow them damps the ringing out, and with
it part of the extremes, without anything the step control (``tension_resolution``)
sees: the damped response is smooth. Nothing but a second run at a finer step shows it.

The check. The run keeps its state at the start of each period; after the run, when
the last period the outputs come from had such an event, that period is run again
from its saved start at half the step and its end tensions' extremes compared with the
run's. They should agree to ``step_tolerance`` of the line's dynamic range (the largest
range of its end tensions in the period, the reference of ``steady_tolerance``), with
the Newton floor of the steady-state test. When they do not, the case keeps its
results (status 0: they are what the study's step gives) and carries a warning naming
both values and an estimate of the steps a period needed: near these events the
response is not smooth, so the error is taken as first order in the step (the halving
changed it by d: the run's own error is about 2 d, and ``points_per_period`` P is
enough when 2 d P / P' is within the tolerance, P' = 2 d P / tolerance).

The re-run starts from the run's own state, so it costs one period at twice the steps
(about two periods' work against the run's ramp plus four or more), and sees the events
of that period; ringing built up over many periods is seen as far as one period of it
shows.

Pure: arrays and numbers in, a :class:`StepVerdict` and a warning text out.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: the warning's kind (:data:`cablestudy.analyses.plausibility.STEP`, one of its KINDS)
STEP = "step"
#: the step of the re-run over the run's step
HALF = 0.5


def snapshot(arrays: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """Copies of a run's state ``arrays`` (name -> array)."""
    return {k: np.array(v, copy=True) for k, v in arrays.items()}


def restore(arrays: dict[str, np.ndarray], saved: dict[str, np.ndarray]) -> None:
    """Put the ``saved`` copies back into the run's ``arrays`` in place (the compiled
    loop holds references to them)."""
    for k, v in saved.items():
        arrays[k][...] = v


@dataclass(frozen=True)
class StepVerdict:
    """The outcome of the check: the end tensions' extremes [N] over the period checked
    at the run's step (``coarse``) and at the re-run's (``fine``), each (ends, 2) (max,
    min), ``names`` of the ends, the tolerance [N] per end, the events that triggered
    it, the run's ``points_per_period`` and the re-run's step factor."""

    coarse: np.ndarray
    fine: np.ndarray
    tolerance: np.ndarray
    names: tuple[str, ...]
    contact_changes: int
    slack_switches: int
    points_per_period: float
    step_tolerance: float
    ranges: np.ndarray
    factor: float = HALF

    @property
    def differences(self) -> np.ndarray:
        """|fine - coarse| [N] (ends, 2)."""
        return np.abs(self.fine - self.coarse)

    @property
    def agrees(self) -> bool:
        """Whether every extreme agrees within its end's tolerance (NaN: no)."""
        return bool(np.all(self.differences <= self.tolerance[:, None]))

    def worst(self) -> tuple[int, int]:
        """(end, 0: max / 1: min) of the largest difference over its tolerance."""
        ratio = self.differences / self.tolerance[:, None]
        ratio = np.where(np.isnan(ratio), np.inf, ratio)
        k = int(np.argmax(ratio))
        return k // 2, k % 2

    def needed_points(self) -> int:
        """``points_per_period`` at which the run's error is expected within the
        tolerance, first order in the step: 2 d P / tolerance (module docstring), at
        least twice the run's."""
        e, m = self.worst()
        d = float(self.differences[e, m])
        tol = float(self.tolerance[e])
        if not (math.isfinite(d) and tol > 0.0):
            return int(math.ceil(self.points_per_period / self.factor))
        need = self.points_per_period * d / ((1.0 - self.factor) * tol)
        return int(math.ceil(max(need, self.points_per_period / self.factor)))


def events_text(contact_changes: int, slack_switches: int) -> str:
    """The events that put the step at risk, in words."""
    parts = []
    if contact_changes:
        parts.append(f"{contact_changes} seabed landings and lift-offs of nodes")
    if slack_switches:
        parts.append(f"{slack_switches} steps with elements going slack or taut")
    return " and ".join(parts)


def step_warning(verdict: StepVerdict) -> str:
    """The warning of a run whose extremes moved by more than the tolerance when the
    step was halved ('' when they agree)."""
    if verdict.agrees:
        return ""
    e, m = verdict.worst()
    what = ("maximum", "minimum")[m]
    p = verdict.points_per_period
    p_fine = p / verdict.factor
    a, b = float(verdict.coarse[e, m]), float(verdict.fine[e, m])
    rng = float(verdict.ranges[e])
    share = abs(b - a) / rng if rng > 0.0 else math.inf
    return (
        f"{STEP}: the {what} tension at {verdict.names[e]} over the last period depends on "
        f"the time step: {a:.6g} N at points_per_period {p:g}, {b:.6g} N with the period run "
        f"again at {p_fine:g} from the same state ({abs(b - a):.4g} N apart, {share:.3g} of "
        f"the period's dynamic range {rng:.4g} N, over analysis.dynamic.step_tolerance "
        f"{verdict.step_tolerance:g}). The period has "
        f"{events_text(verdict.contact_changes, verdict.slack_switches)}, which ring modes "
        f"the step damps instead of resolving. The values reported are those at {p:g}: "
        f"about points_per_period {verdict.needed_points()} is needed (a first-order "
        "estimate: run there and compare), or the line's axial damping (segments' "
        "damping_ratio) where the real line has it"
    )


def failed_warning(message: str, points_per_period: float) -> str:
    """The warning of a check whose re-run at half the step failed (``message``)."""
    return (
        f"{STEP}: not verified: the last period run again at half the step "
        f"(points_per_period {points_per_period * 2:g}) failed ({message}), the values "
        f"reported are those at {points_per_period:g}"
    )


def verdict_of(
    coarse: np.ndarray,
    fine: np.ndarray,
    ranges: np.ndarray,
    *,
    names: tuple[str, ...],
    step_tolerance: float,
    floor: float,
    contact_changes: int,
    slack_switches: int,
    points_per_period: float,
    factor: float = HALF,
    line_of_end: np.ndarray | None = None,
) -> StepVerdict:
    """The check's verdict from the extremes (ends, 2) at the run's step and the
    re-run's, the ends' tension ranges in the period [N] (ends,) and the Newton
    ``floor`` [N]. Each end's tolerance is ``step_tolerance`` times the largest range
    among the ends of its line (``line_of_end`` (ends,), None: one line), at least the
    floor."""
    ranges = np.asarray(ranges, dtype=float)
    lines = np.zeros(ranges.size, dtype=int) if line_of_end is None else np.asarray(line_of_end)
    line_range = np.array([np.nanmax(ranges[lines == lines[k]]) for k in range(ranges.size)])
    tol = np.maximum(step_tolerance * line_range, floor)
    return StepVerdict(
        coarse=np.asarray(coarse, dtype=float),
        fine=np.asarray(fine, dtype=float),
        tolerance=tol,
        names=names,
        contact_changes=int(contact_changes),
        slack_switches=int(slack_switches),
        points_per_period=float(points_per_period),
        step_tolerance=float(step_tolerance),
        ranges=line_range,
        factor=factor,
    )
