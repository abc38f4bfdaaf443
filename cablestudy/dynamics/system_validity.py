"""When a system's frequency-domain (linear) answer can be trusted: ``method: auto``
for a mooring system (issue 24). Pure: arrays in, numbers and words out.

The single line's checks (:mod:`cablestudy.dynamics.validity`: near slack, amplitude
against sag, touchdown travel for lines on the seabed) are applied to every line of
the system on its own response in the system's harmonic solution
(:class:`~cablestudy.dynamics.system_frequency.SystemFrequencyResult`): its nodal
displacements, element and end tension amplitudes against its static tensions. The
frequency domain is trusted only when every line passes; the line that decides is
named: the first line that fails (with all of its failed checks), or when all pass
the line nearest its limits (the largest share of a threshold used).

One measure differs from the single line's: the geometric one takes the nodes'
displacement relative to the motion of the line's chord, ``u(s) - (1 - s/L) u_A -
(s/L) u_B`` (``L`` the unstretched length), over the sag. A single line is held at
one end, where the two agree within the other end's motion; but in a system both ends
of a line move (a bridle between a spar and a junction, a leg between an anchor and
a junction), and the rigid translation and the axial stretch of a taut line change
no shape: they carry none of the geometric terms the linearisation drops. Measured on
MoorPy's case8 surged 0.1 m at 0.1 Hz (21 nodes a line): the total displacement over
the sag is 3.1 to 3.3 on the bridles (sag 3 cm, both ends moving about 0.09 to 0.1 m
together) and 0.42 on the legs, where the frequency domain agrees with the time
domain within 2.1e-3 of the largest tension amplitude; relative to the chord, 0.012
to 0.03. On MoorDyn's lines.txt (chains, anchored) both are 5e-3 at 0.2 m.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from .frequency_model import sum_components
from .validity import Validity, measures_cases, sag

if TYPE_CHECKING:
    from ..study.analysis import AutoSettings


def system_measures(
    model: object,
    result: object,
    on_seabed: Sequence[np.ndarray],
    submerged_weight: Sequence[np.ndarray],
) -> list[Validity]:
    """The validity measures of every line of a solved system response.

    ``model`` a :class:`~.system_frequency.SystemLinear`, ``result`` its
    :class:`~.system_frequency.SystemFrequencyResult` (status 0); per line
    ``on_seabed`` (n_l,) bool, the nodes laid on the seabed in the static state, and
    ``submerged_weight`` [N/m] (n_l,) at the nodes. The geometric measure is on the
    displacement relative to the chord's motion (module docstring).

    All lines at once (flat over their nodes and elements; a line with a laid stretch
    and a touchdown point goes through :func:`~.validity.measures_cases` on its own, for
    its touchdown travel): each quantity by the same operations on the same numbers as
    :func:`~.validity.measures_cases` line by line, and the minima and maxima are exact
    whatever the order, so the measures are the same numbers
    (tests/unit/test_system_validity.py)."""
    lines = [red.line for red in model.lines]  # type: ignore[attr-defined]
    L = len(lines)
    if L == 0:
        return []
    n = np.array([ln.n_nodes for ln in lines], dtype=np.int64)
    node_start = np.concatenate(([0], np.cumsum(n)))
    el_start = np.concatenate(([0], np.cumsum(n - 1)))
    of_node = np.repeat(np.arange(L), n)
    of_el = np.repeat(np.arange(L), n - 1)
    first, last = node_start[:-1], node_start[1:] - 1
    s = np.concatenate([ln.s for ln in lines])
    disp = result.displacement  # type: ignore[attr-defined]
    u = np.concatenate(disp) if isinstance(disp, list | tuple) else np.asarray(disp)
    # the displacement relative to the chord's motion, its largest amplitude per line
    xi = ((s - s[first][of_node]) / (s[last] - s[first])[of_node])[:, None]
    deformation = u - (1.0 - xi) * u[first][of_node] - xi * u[last][of_node]
    amp = np.maximum.reduceat(np.sqrt(sum_components(np.abs(deformation) ** 2)), first)
    # near slack: elements between two held nodes, and laid ones (nodes on the seabed)
    # without static tension, and laid ends without it, left out (as slack_ratio)
    bed = np.concatenate([np.asarray(b, dtype=bool) for b in on_seabed])
    held = np.concatenate(
        [np.diff(ln.free_basis.tocsr().indptr).reshape(-1, 3).sum(axis=1) == 0 for ln in lines]
    )
    left = np.delete(np.arange(s.size), last)  # each element's first node
    t_el = np.concatenate([ln.tension for ln in lines])
    a_el = np.abs(np.concatenate(result.element_tension))  # type: ignore[attr-defined]
    t_end = np.asarray(result.tension_static, dtype=float).reshape(L, 2)  # type: ignore[attr-defined]
    a_end = np.abs(np.asarray(result.end_tension)).reshape(L, 2)  # type: ignore[attr-defined]
    keep_el = ~(held[left] & held[left + 1])
    keep_el &= ~(bed[left] & bed[left + 1] & (t_el <= 0.0))
    keep_end = ~(np.stack([bed[first], bed[last]], axis=1) & (t_end <= 0.0))
    static = np.concatenate([t_el[keep_el], t_end[keep_end]])
    amps = np.concatenate([a_el[keep_el], a_end[keep_end]])
    which = np.concatenate([of_el[keep_el], np.repeat(np.arange(L), 2)[keep_end.ravel()]])
    top = np.zeros(L)
    np.maximum.at(top, which, static)
    positive = static > 0.0
    active = positive | (amps > 1e-12 * top[which])
    with np.errstate(divide="ignore", invalid="ignore"):
        ratios = np.where(
            positive,
            (static - amps) / np.where(positive, static, 1.0),
            -amps / np.maximum(top[which], amps),
        )
    slack = np.full(L, math.inf)
    np.minimum.at(slack, which[active], ratios[active])
    out = []
    for i, line in enumerate(lines):
        b = bed[first[i] : last[i] + 1]
        laid = float(np.sum(line.rest_length[b[:-1] & b[1:]]))
        if laid > 0.0 and np.any(b) and not np.all(b):  # a touchdown point: on its own
            ratio, amp_ratio, travel = measures_cases(
                s=line.s,
                position=line.position,
                displacement=deformation[first[i] : last[i] + 1][None],
                element_tension_static=line.tension,
                element_tension_amplitude=a_el[el_start[i] : el_start[i + 1]][None],
                end_tension_static=t_end[i],
                end_tension_amplitude=a_end[i][None],
                laid_length=laid,
                on_seabed=b,
                submerged_weight=np.asarray(submerged_weight[i], dtype=float),
                held=held[first[i] : last[i] + 1],
            )
            out.append(
                Validity(
                    min_tension_ratio=float(ratio[0]),
                    amplitude_sag_ratio=float(amp_ratio[0]),
                    touchdown_travel=float(travel[0]),
                )
            )
            continue
        length = float(line.s[-1] - line.s[0])
        d = sag(line.position)
        out.append(
            Validity(
                min_tension_ratio=float(slack[i]),
                amplitude_sag_ratio=float(amp[i] / (d if d > 1e-9 * length else length)),
                touchdown_travel=0.0,
            )
        )
    return out


def line_failures(v: Validity, auto: AutoSettings) -> list[str]:
    """The checks of ``method: auto`` (``auto``: its
    :class:`~cablestudy.config.analysis.AutoSettings`) one line's measures fail, in
    words (empty: it passes)."""
    reasons = []
    if v.min_tension_ratio < auto.min_tension_ratio:
        reasons.append(
            f"near slack: min/static tension {v.min_tension_ratio:.3g} < {auto.min_tension_ratio:g}"
        )
    if v.amplitude_sag_ratio > auto.max_amplitude_sag_ratio:
        reasons.append(
            f"large motion: amplitude/sag {v.amplitude_sag_ratio:.3g} > "
            f"{auto.max_amplitude_sag_ratio:g}"
        )
    if not math.isfinite(v.touchdown_travel):
        reasons.append("touchdown travel unbounded: no submerged weight at the touchdown point")
    elif v.touchdown_travel > auto.max_touchdown_travel:
        reasons.append(
            f"touchdown travel {v.touchdown_travel:.3g} L > {auto.max_touchdown_travel:g} L"
        )
    return reasons


def _share(v: Validity, auto: AutoSettings) -> float:
    """The largest share of a threshold a passing line uses (1: at a limit)."""
    slack_room = 1.0 - auto.min_tension_ratio
    shares = [
        (1.0 - v.min_tension_ratio) / slack_room if slack_room > 0.0 else 0.0,
        v.amplitude_sag_ratio / auto.max_amplitude_sag_ratio
        if auto.max_amplitude_sag_ratio > 0.0
        else 0.0,
        v.touchdown_travel / auto.max_touchdown_travel if auto.max_touchdown_travel > 0.0 else 0.0,
    ]
    return max(shares)


def judge_system(
    names: Sequence[str], validities: Sequence[Validity], auto: AutoSettings
) -> tuple[bool, str]:
    """(trusted, reason): the frequency domain is trusted when every line passes
    :func:`line_failures`; the reason names the deciding line (module docstring)."""
    for name, v in zip(names, validities, strict=True):
        failed = line_failures(v, auto)
        if failed:
            return False, f"line {name!r}: {'; '.join(failed)}"
    k = int(np.argmax([_share(v, auto) for v in validities]))
    v = validities[k]
    return True, (
        f"linear (every line within the limits; nearest, line {names[k]!r}: min/static "
        f"tension {v.min_tension_ratio:.3g}, amplitude/sag {v.amplitude_sag_ratio:.3g}, "
        f"touchdown travel {v.touchdown_travel:.3g} L)"
    )


__all__ = ["judge_system", "line_failures", "system_measures"]
