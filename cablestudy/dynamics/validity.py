"""When a frequency-domain (linear) answer can be trusted: the checks of ``method:
auto``. Pure: arrays in, numbers out.

* **Slack.** The linear model keeps every element taut. The smallest ratio of
  (static - amplitude) to static tension over the elements (and the end tensions)
  measures how near the line comes to slack; below ``min_tension_ratio`` the time
  domain runs (taut-slack snapping is outside any linearisation).
* **Geometry.** The linearisation drops terms of order (displacement / sag) against
  one: the largest nodal displacement amplitude over the sag (largest distance of the
  static line from the chord between its ends) must stay below
  ``max_amplitude_sag_ratio``. A line with no sag (straight) uses its length instead.
* **Drag.** The drag linearisation must have converged.
* **Touchdown.** The laid nodes are held (:mod:`cablestudy.dynamics.linear_model`);
  that stands only while the touchdown point stays put. A catenary leaving the seabed
  horizontally with tension ``H`` and rising ``h`` over its suspended length ``s``
  has ``s^2 = h^2 + 2 h H / w`` (inextensible; ``w`` submerged weight per length), so
  a tension change ``dH`` at the touchdown point moves it along the bed by
  ``ds = h dH / (w s)`` (``w s`` the vertical tension at the top of the suspended
  stretch): the tension amplitude of the element at the touchdown point gives the
  travel amplitude, which over the line length must stay below
  ``max_touchdown_travel``. (On the chain of configs/chain-mooring-surge.yaml this
  gives 8.5 m per metre of surge; the static laid length changes by 8.6, 17.2 and
  34.6 m for +-1, 2, 4 m. An earlier estimate from the vertical amplitude ``dz`` of
  the first suspended node, ``sqrt(2 dz / kappa)`` with ``kappa = w / H``, grew as
  the square root of the amplitude and depended on where that node sat: 11.4, 16.2,
  22.8 m there.)
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .frequency_model import sum_components


@dataclass(frozen=True, kw_only=True)
class Validity:
    """The measures of the module docstring for one harmonic response."""

    min_tension_ratio: float
    amplitude_sag_ratio: float
    touchdown_travel: float  # over the line length [-]


def sag(position: np.ndarray) -> float:
    """Largest distance [m] of the points ``position`` (n, 3) from the chord of the two
    end points."""
    chord = position[-1] - position[0]
    length = float(np.linalg.norm(chord))
    rel = position - position[0]
    if length == 0.0:
        return float(np.max(np.linalg.norm(rel, axis=1)))
    along = rel @ (chord / length)
    return float(np.max(np.linalg.norm(rel - along[:, None] * (chord / length), axis=1)))


def slack_ratio(
    *,
    element_tension_static: np.ndarray,
    element_tension_amplitude: np.ndarray,
    end_tension_static: np.ndarray,
    end_tension_amplitude: np.ndarray,
    on_seabed: np.ndarray,
    held: np.ndarray | None = None,
) -> np.ndarray:
    """The slack measure of K responses (K,): the smallest (static - amplitude) / static
    tension over the elements (n - 1,) and the ends (2,) that can go slack, with the
    amplitudes (K, n - 1) and (K, 2) [N].

    Left out: elements between two ``held`` nodes (they do not move), and elements and
    ends laid on the seabed (``on_seabed`` (n,)) with no static tension (a laid stretch
    or an anchor that friction has emptied of tension lies on the seabed; it is not a
    slack span). A suspended point with no static tension that moves is measured
    against the line's largest static tension, ``-amplitude / max(T_max, amplitude)``
    (finite, below zero: slack). No point to measure: +inf (nothing can go slack)."""
    keep = np.ones(element_tension_static.size, dtype=bool)
    if held is not None:
        keep = ~(held[:-1] & held[1:])
    laid = np.asarray(on_seabed, dtype=bool)
    keep &= ~(laid[:-1] & laid[1:] & (element_tension_static <= 0.0))
    keep_end = ~(laid[[0, -1]] & (end_tension_static <= 0.0))
    static = np.concatenate([element_tension_static[keep], end_tension_static[keep_end]])
    amp = np.concatenate(
        [element_tension_amplitude[:, keep], end_tension_amplitude[:, keep_end]], axis=1
    )
    top = float(np.max(static, initial=0.0))
    positive = static > 0.0
    # a point with no static tension and no motion is not near slack; one with motion is
    active = positive[None] | (amp > 1e-12 * top)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratios = np.where(
            positive[None],
            (static - amp) / np.where(positive, static, 1.0)[None],
            -amp / np.maximum(top, amp),
        )
    return np.min(np.where(active, ratios, math.inf), axis=1, initial=math.inf)


def measures_cases(
    *,
    s: np.ndarray,
    position: np.ndarray,
    displacement: np.ndarray,
    element_tension_static: np.ndarray,
    element_tension_amplitude: np.ndarray,
    end_tension_static: np.ndarray,
    end_tension_amplitude: np.ndarray,
    laid_length: float,
    on_seabed: np.ndarray,
    submerged_weight: np.ndarray,
    held: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Validity measures of K responses of one line at once. ``s`` [m] (n,), ``position``
    [m] (n, 3) static nodes, ``displacement`` [m] (K, n, 3) complex amplitudes; tensions
    [N]: static per element (n - 1,) and at the ends (2,), amplitudes per response (K, n -
    1) and (K, 2); ``laid_length`` [m]; ``on_seabed`` (n,) bool, the held laid nodes;
    ``submerged_weight`` [N/m] (n,) at the nodes; ``held`` (n,) bool, nodes with no free
    direction (elements between two of them do not move and are left out of the slack
    check: a laid stretch that friction has emptied of tension is not a slack span).
    Returns (min_tension_ratio, amplitude_sag_ratio, touchdown_travel), each (K,)."""
    ratio = slack_ratio(
        element_tension_static=element_tension_static,
        element_tension_amplitude=element_tension_amplitude,
        end_tension_static=end_tension_static,
        end_tension_amplitude=end_tension_amplitude,
        on_seabed=on_seabed,
        held=held,
    )
    length = float(s[-1] - s[0])
    d = sag(position)
    a = np.max(np.sqrt(sum_components(np.abs(displacement) ** 2)), axis=1)
    K = displacement.shape[0]
    travel = np.zeros(K)
    if laid_length > 0.0 and np.any(on_seabed) and not np.all(on_seabed):
        n = on_seabed.size
        travels = []
        for e in np.flatnonzero(np.diff(on_seabed.astype(int)) != 0):
            k, step = (e, 1) if on_seabed[e] else (e + 1, -1)
            stretch = [k + step]
            while 0 <= stretch[-1] + step < n and not on_seabed[stretch[-1] + step]:
                stretch.append(stretch[-1] + step)
            top = stretch[-1]
            h = float(np.max(position[stretch, 2]) - position[k, 2])
            w = max(float(submerged_weight[k]), 0.0)
            v_top = w * abs(float(s[top] - s[k]))
            d_t = element_tension_amplitude[:, min(e, element_tension_amplitude.shape[1] - 1)]
            travels.append(h * d_t / v_top if v_top > 0.0 else np.full(K, math.inf))
        travel = np.max(np.stack(travels), axis=0) / length
    return ratio, a / (d if d > 1e-9 * length else length), travel
