"""The study behind the defaults of ``method: auto`` (analysis.dynamic.auto).

Runs the moustafa Figs. 2-5 sweep (configs/moustafa-figs2-5.yaml: 4 amplitudes x 23
frequencies) twice through the CLI, with ``method: auto`` and ``method: time``, and
also records for every case the frequency-domain answer and its validity measures
(min/static tension ratio, amplitude/sag), so that the thresholds can be read off.
Writes ``auto-vs-time.png`` and ``auto-study.json`` next to this file.

Usage: ``python docs/frequency-domain/auto_study.py [OUT_DIR]`` (results go to
OUT_DIR, default results/auto-study).
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402

from cablestudy import analyses  # noqa: E402
from cablestudy.cases import expand_cases  # noqa: E402
from cablestudy.config.analysis import AutoSettings  # noqa: E402
from cablestudy.config.loader import parse_study_text  # noqa: E402
from cablestudy.frequency_cases import solve_frequency  # noqa: E402

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[1]
CONFIG = REPO / "configs" / "moustafa-figs2-5.yaml"


def run(out: Path, method: str) -> xr.Dataset:
    text = CONFIG.read_text().replace("method: auto", f"method: {method}")
    text = text.replace("name: moustafa-figs2-5", f"name: figs2-5-{method}")
    cfg = out / f"figs2-5-{method}.yaml"
    cfg.write_text(text)
    subprocess.run(
        [sys.executable, "-m", "cablestudy", "run", str(cfg), "--out", str(out), "--no-cache"],
        check=True,
    )
    return xr.load_dataset(out / f"figs2-5-{method}.nc")


def frequency_answers() -> list[dict]:
    """Frequency-domain max/min and validity measures of every case."""
    _, cases = expand_cases(parse_study_text(CONFIG.read_text()))
    rows = []
    for case in cases:
        static = analyses.solve_static(case, None)
        res = solve_frequency(case, static, None)
        assert res.validity is not None, res.message
        rows.append(
            {
                "index": list(case.index),
                "tension_max": float(res.data["tension_max"]),
                "tension_min": float(res.data["tension_min"]),
                "min_tension_ratio": res.validity.min_tension_ratio,
                "amplitude_sag_ratio": res.validity.amplitude_sag_ratio,
                "drag_converged": res.drag_converged,
            }
        )
    return rows


def main(out: Path) -> None:
    out.mkdir(parents=True, exist_ok=True)
    auto, time_ = run(out, "auto"), run(out, "time")
    rows = frequency_answers()
    defaults = AutoSettings()
    tmax, tmin = time_["tension_max"].values, time_["tension_min"].values
    err = np.full(tmax.shape, np.nan)
    ratio, sag = np.full(tmax.shape, np.nan), np.full(tmax.shape, np.nan)
    for r in rows:
        i, j = r["index"]
        err[i, j] = max(
            abs(r["tension_max"] / tmax[i, j] - 1.0), abs(r["tension_min"] / tmin[i, j] - 1.0)
        )
        ratio[i, j], sag[i, j] = r["min_tension_ratio"], r["amplitude_sag_ratio"]
    chose = auto["dynamic_method"].values == "frequency"
    auto_err = np.maximum(
        np.abs(auto["tension_max"].values / tmax - 1.0),
        np.abs(auto["tension_min"].values / tmin - 1.0),
    )
    summary = {
        "cases": int(chose.size),
        "auto_chose_frequency": int(np.count_nonzero(chose)),
        "largest_error_where_frequency_chosen": float(np.max(auto_err[chose]))
        if chose.any()
        else None,
        "thresholds": defaults.model_dump(),
        "frequency_domain_error_all_cases": np.round(err, 5).tolist(),
        "amplitude_sag_ratio": np.round(sag, 5).tolist(),
        "min_tension_ratio": np.round(ratio, 5).tolist(),
    }
    (HERE / "auto-study.json").write_text(json.dumps(summary, indent=1))

    fig, axes = plt.subplots(2, 3, figsize=(14, 7.5))
    f = time_["frequency"].values
    for k, ax in enumerate(axes.flat[:4]):
        amp = float(time_["amplitude"][k])
        for var, style in (("tension_max", "-"), ("tension_min", "--")):
            ax.plot(f, time_[var].values[k], style, color="k", lw=1, label=f"time {var[8:]}")
            fd = np.array([r[var] for r in rows if r["index"][0] == k])
            ax.plot(f, fd, style, color="C0", lw=1, label=f"frequency {var[8:]}")
            a = auto[var].values[k]
            ax.plot(f[chose[k]], a[chose[k]], "o", color="C0", ms=4)
            ax.plot(f[~chose[k]], a[~chose[k]], "o", mfc="none", color="C3", ms=5)
        ax.set_title(f"amplitude {amp:g} m (auto: filled = frequency, open = time)", fontsize=9)
        ax.set_xlabel("excitation frequency [Hz]")
        ax.set_ylabel("tension at B [N]")
        ax.grid(alpha=0.3)
        if k == 0:
            ax.legend(fontsize=7)
    ax = axes.flat[4]
    sc = ax.scatter(sag.ravel(), 100 * err.ravel(), c=ratio.ravel(), cmap="viridis", s=14)
    ax.axvline(defaults.max_amplitude_sag_ratio, color="C3", lw=1)
    ax.axhline(2.0, color="k", lw=0.8, ls=":")
    ax.set_xlabel("largest displacement amplitude / sag [-]")
    ax.set_ylabel("frequency vs time domain, max |dT| / T [%]")
    ax.set_yscale("log")
    fig.colorbar(sc, ax=ax, label="min / static tension [-]")
    ax.grid(alpha=0.3)
    ax = axes.flat[5]
    ax.scatter(ratio.ravel(), 100 * err.ravel(), c=sag.ravel(), cmap="magma", s=14)
    ax.axvline(defaults.min_tension_ratio, color="C3", lw=1)
    ax.axhline(2.0, color="k", lw=0.8, ls=":")
    ax.set_xlabel("min / static tension along the line [-]")
    ax.set_yscale("log")
    ax.grid(alpha=0.3)
    largest = summary["largest_error_where_frequency_chosen"]
    fig.suptitle(
        "method auto on the Figs. 2-5 sweep: frequency chosen for "
        f"{summary['auto_chose_frequency']} of 92 cases, largest max/min difference to the "
        f"time domain there {100 * (largest or 0):.2f} % (red lines: default thresholds)",
        fontsize=10,
    )
    fig.tight_layout()
    fig.savefig(HERE / "auto-vs-time.png", dpi=110)
    print(
        json.dumps(
            {
                k: summary[k]
                for k in ("cases", "auto_chose_frequency", "largest_error_where_frequency_chosen")
            }
        )
    )


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else REPO / "results" / "auto-study")
