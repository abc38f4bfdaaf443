"""Small-amplitude resonance of the time-domain model against our modal analysis.

The same cable (the moustafa seed's, in vacuum so nothing damps it) is rung by a small
smooth pulse of end B along the span; the spectral peak of the end tension between
1.4 and 2.2 Hz is the first symmetric in-plane mode (see test_dynamics_irvine.py). The
modal analysis about the static shape, on the same number of uniform elements, must
predict it. Both are lumped-mass chains of 40 elements; they differ by the state they
linearise about (the dynamic model's own discrete equilibrium, the modal model's
samples of the continuous catenary), an O(h^2) difference of about 0.1 % here, plus
the integrator's period elongation (~0.05 % at 64 steps per period of 0.3125 s) and the
spectral read-out (~0.1 %): 0.5 % in all. Irvine's shallow theory, by contrast, is only
good to ~2 % on this cable (sag/span 0.081), so this is the sharper check of both the
integrator and the eigenproblem.
"""

from __future__ import annotations

import numpy as np
import yaml

from cablestudy.analyses.evaluate import evaluate_case
from cablestudy.study.grid import expand_cases
from cablestudy.study.loader import parse_study_text

from .dynamics_helpers import moustafa_study, ring_after_pulse
from .test_dynamics_irvine import dominant_frequency

BAND = (1.4, 2.2)


def test_free_vibration_peak_matches_the_modal_frequency() -> None:
    t, tension = ring_after_pulse()
    measured = dominant_frequency(t[t > 2.0], tension[t > 2.0], BAND)

    modal_study = moustafa_study(fluid="vacuum")
    modal_study["analysis"] = {
        "static": modal_study["analysis"]["static"],
        "modal": {"modes": 8, "elements": 40, "mesh": "uniform"},
    }
    _, cases = expand_cases(parse_study_text(yaml.safe_dump(modal_study), "<modal>"))
    record = evaluate_case(cases[0])
    assert record.status == 0, record.message
    freqs = np.asarray(record.data["natural_frequency"])
    in_band = freqs[(freqs > BAND[0]) & (freqs < BAND[1])]
    # out-of-plane modes do not load the end tension at first order; the in-plane
    # symmetric mode is the one the pulse excites, and it must be among the modes
    # (measured 1.6794 Hz against 1.6809 Hz, 0.09 %; the other mode in the band, the
    # second out-of-plane one at 1.768 Hz, is 5 % away)
    nearest = float(in_band[np.argmin(np.abs(in_band - measured))])
    assert abs(measured - nearest) <= 0.005 * nearest, (measured, in_band)
