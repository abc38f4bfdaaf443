"""method: auto against the time domain on the chain mooring (configs/
chain-mooring-surge.yaml: 310 m of chain on the seabed at rest, friction 0.5), a
subset of the study of docs/frequency-domain.md: surge 0.5, 1, 2 m at slow drift
(80 s), 12.5 s and 8 s. Auto keeps the frequency domain for six of the nine (touchdown
travel up to 0.022 L, within the default 0.03 L) and there max and min fairlead tension
agree with a pure time-domain run within 2 % (the issue's bound; the study measured
1.23 % at most, at 1 m and 12.5 s); it refuses the other three, among them 2 m at 8 s,
where the linear minimum is 10 % off (near slack, and the touchdown travels 0.16 L)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from cablestudy.analyses.evaluate import evaluate_chunk
from cablestudy.analyses.frequency import solve_frequency
from cablestudy.analyses.static import solve_static
from cablestudy.study.grid import expand_cases
from cablestudy.study.loader import parse_study_text

CONFIG = Path(__file__).resolve().parents[2] / "configs" / "chain-mooring-surge.yaml"
AMPLITUDES = [0.5, 1.0, 2.0]
FREQUENCIES = [0.0125, 0.08, 0.125]


def _text(method: str) -> str:
    text = CONFIG.read_text()
    for old, new in (
        ("method: time", f"method: {method}"),
        ("[1.0, 2.0, 4.0]", str(AMPLITUDES)),
        ("[0.01, 0.0125, 0.08, 0.1, 0.125]", str(FREQUENCIES)),
    ):
        assert old in text
        text = text.replace(old, new)
    return text


def test_auto_on_the_chain_keeps_the_frequency_domain_only_where_it_agrees() -> None:
    _, cases = expand_cases(parse_study_text(_text("auto")))
    auto = evaluate_chunk(cases)
    time_ = evaluate_chunk(expand_cases(parse_study_text(_text("time")))[1])
    assert all(r.status == 0 for r in auto + time_)
    chose = np.array([str(r.data["dynamic_method"]) == "frequency" for r in auto])
    reasons = [str(r.data["dynamic_method_reason"]) for r in auto]
    # both choices occur: slow drift and small motion kept, large wave-frequency refused
    assert chose.sum() >= 5 and (~chose).sum() >= 2, reasons
    for key in ("tension_max", "tension_min"):
        a = np.array([float(r.data[key]) for r in auto])
        t = np.array([float(r.data[key]) for r in time_])
        assert np.all(np.abs(a[chose] / t[chose] - 1.0) < 0.02), (key, a / t - 1.0)
        np.testing.assert_allclose(a[~chose], t[~chose], rtol=1e-12)
    # 2 m at 8 s (the last case): the linear answer is more than 2 % off, auto refuses
    # it and says why
    worst = cases[-1]
    assert worst.coords == {"amplitude": 2.0, "frequency": 0.125}
    static = solve_static(worst, None)
    fd = solve_frequency(worst, static, None)
    t_min = float(time_[-1].data["tension_min"])
    assert abs(float(fd.data["tension_min"]) / t_min - 1.0) > 0.02
    assert not chose[-1]
    assert ("touchdown travel" in reasons[-1]) or ("near slack" in reasons[-1]), reasons[-1]


def test_touchdown_travel_estimate_matches_the_static_laid_length_change() -> None:
    """At slow drift (100 s) the touchdown moves quasi-statically: the estimate of
    cablestudy/dynamics/validity.py (catenary, ``h dH / (w s)`` from the linear tension
    amplitude at the touchdown point) against half the change of the static laid length
    between the fairlead moved by -a and +a. Bound 2 %: the estimate is linear and
    inextensible (T/EA about 1.5e-3); the laid length is not linear in the offset (at
    2 m, half the +-2 m change is 17.25 m against 2 x 8.62 m at +-1 m: 0.1 %). Measured:
    8.65 and 17.30 m against 8.62 and 17.25 m (0.3 %)."""
    text = CONFIG.read_text()
    for amplitude in (1.0, 2.0):
        study = text.replace("[1.0, 2.0, 4.0]", f"[{amplitude}]").replace(
            "[0.01, 0.0125, 0.08, 0.1, 0.125]", "[0.01]"
        )
        case = expand_cases(parse_study_text(study))[1][0]
        v = solve_frequency(case, solve_static(case, None), None).validity
        assert v is not None
        laid = []
        for dx in (-amplitude, amplitude):
            moved = study.replace("[750.0, 0.0, -10.0]", f"[{750.0 + dx}, 0.0, -10.0]")
            c = expand_cases(parse_study_text(moved))[1][0]
            laid.append(solve_static(c, None).laid_length)
        static_travel = 0.5 * (laid[0] - laid[1])  # moving out lifts chain off the bed
        np.testing.assert_allclose(v.touchdown_travel * 800.0, static_travel, rtol=0.02)
