"""The touchdown point's range of travel in the frequency domain (``touchdown_min``,
``touchdown_max``), which the time domain measures step by step.

The linear model holds the laid nodes, so its own touchdown point does not move; its
travel is the catenary estimate that ``method: auto`` checks
(:func:`cablestudy.dynamics.validity.measures_cases`: a tension change dH at the
touchdown point moves it by h dH / (w s), h the rise and w s the vertical tension at
the top of the suspended stretch; on the chain mooring it matches the static laid
length's change to 3 digits, docs/frequency-domain.md). The point itself is the time
domain's: where the first run of nodes on the seabed seen from end A meets the
suspended span (the end of that run when A lies on the seabed, its start otherwise).
"""

from __future__ import annotations

import numpy as np


def touchdown_range(
    s: np.ndarray, on_seabed: np.ndarray, travel: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """(least, greatest) arc length [m] from end A of the touchdown point, each (K,), of
    K linear responses of one line: its nodes at unstretched arc lengths ``s`` [m] (n,),
    which of them rest on the seabed ``on_seabed`` (n,) bool, and each response's
    touchdown travel amplitude over the line length ``travel`` [-] (K,). NaN where the
    line does not both rest on the seabed and hang from it, or the estimate is not
    finite."""
    s = np.asarray(s, dtype=float)
    on = np.asarray(on_seabed, dtype=bool)
    travel = np.asarray(travel, dtype=float)
    nan = np.full(travel.shape, np.nan)
    if not on.any() or on.all():
        return nan, nan.copy()
    # the last node of the run laid from A, or the first laid node seen from A
    point = s[int(np.argmin(on)) - 1] if on[0] else s[int(np.argmax(on))]
    reach = np.where(np.isfinite(travel), travel * float(s[-1] - s[0]), np.nan)
    return point - reach, point + reach
