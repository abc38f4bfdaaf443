"""The study behind the defaults of ``method: auto`` (analysis.dynamic.auto).

Two sweeps, each run through the CLI with ``method: auto`` and ``method: time``, with
the frequency-domain answer and its validity measures (min/static tension ratio,
amplitude/sag, touchdown travel) recorded for every case, so that the thresholds can
be read off:

* the moustafa Figs. 2-5 sweep (configs/moustafa-figs2-5.yaml: 4 amplitudes x 23
  frequencies; no seabed): ``auto-vs-time.png``, ``auto-study.json``;
* the chain mooring (configs/chain-mooring-surge.yaml, 310 m of chain on the seabed at
  rest, friction 0.5) in surge, amplitudes 0.25-4 m x frequencies 0.01-0.125 Hz:
  ``auto-vs-time-chain.png``, ``auto-study-chain.json``.

Usage: ``python docs/frequency-domain/auto_study.py [OUT_DIR] [figs2-5|chain]``
(results go to OUT_DIR, default results/auto-study; both sweeps unless one is named).
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
from cablestudy.analyses.frequency import solve_frequency  # noqa: E402
from cablestudy.study.analysis import AutoSettings  # noqa: E402
from cablestudy.study.grid import expand_cases  # noqa: E402
from cablestudy.study.loader import parse_study_text  # noqa: E402

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[1]
CONFIG = REPO / "configs" / "moustafa-figs2-5.yaml"
CHAIN = REPO / "configs" / "chain-mooring-surge.yaml"
#: the chain sweep: amplitudes from well inside the linear range to near slack; slow
#: drift (periods 100 s, 80 s), an intermediate 20 s and wave periods 12.5-8 s
CHAIN_AMPLITUDES = [0.25, 0.5, 1.0, 2.0, 3.0, 4.0]
CHAIN_FREQUENCIES = [0.01, 0.0125, 0.05, 0.08, 0.1, 0.125]


def run_text(out: Path, name: str, text: str) -> xr.Dataset:
    """Run the study ``text`` (named ``name``) through the CLI; its dataset."""
    cfg = out / f"{name}.yaml"
    cfg.write_text(text)
    subprocess.run(
        [sys.executable, "-m", "cablestudy", "run", str(cfg), "--out", str(out), "--no-cache"],
        check=True,
    )
    return xr.load_dataset(out / f"{name}.nc")


def figs_text(method: str) -> str:
    text = CONFIG.read_text().replace("method: auto", f"method: {method}")
    return text.replace("name: moustafa-figs2-5", f"name: figs2-5-{method}")


def chain_text(
    method: str,
    amplitudes: list[float] = CHAIN_AMPLITUDES,
    frequencies: list[float] = CHAIN_FREQUENCIES,
) -> str:
    """The chain mooring study with ``method`` and the given sweep."""
    text = CHAIN.read_text()
    for old, new in (
        ("method: time", f"method: {method}"),
        ("name: chain-mooring-surge", f"name: chain-{method}"),
        ("[1.0, 2.0, 4.0]", json.dumps(list(amplitudes))),
        ("[0.01, 0.0125, 0.08, 0.1, 0.125]", json.dumps(list(frequencies))),
    ):
        assert old in text, old
        text = text.replace(old, new)
    return text


def frequency_answers(text: str) -> list[dict]:
    """Frequency-domain max/min and validity measures of every case of ``text``."""
    _, cases = expand_cases(parse_study_text(text))
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
                "touchdown_travel": res.validity.touchdown_travel,
                "drag_converged": res.drag_converged,
            }
        )
    return rows


def compare(auto: xr.Dataset, time_: xr.Dataset, rows: list[dict]) -> dict[str, np.ndarray]:
    """Per case (sweep shape): the frequency domain's signed and largest relative
    differences to the time domain in max and min, its validity measures, auto's choice
    and auto's own difference to the time domain."""
    tmax, tmin = time_["tension_max"].values, time_["tension_min"].values
    nan = lambda: np.full(tmax.shape, np.nan)  # noqa: E731
    c = {k: nan() for k in ("d_max", "d_min", "ratio", "sag", "travel")}
    c["fmax"], c["fmin"] = nan(), nan()
    for r in rows:
        i, j = r["index"]
        c["fmax"][i, j], c["fmin"][i, j] = r["tension_max"], r["tension_min"]
        c["d_max"][i, j] = r["tension_max"] / tmax[i, j] - 1.0
        c["d_min"][i, j] = r["tension_min"] / tmin[i, j] - 1.0
        c["ratio"][i, j], c["sag"][i, j] = r["min_tension_ratio"], r["amplitude_sag_ratio"]
        c["travel"][i, j] = r["touchdown_travel"]
    c["err"] = np.maximum(np.abs(c["d_max"]), np.abs(c["d_min"]))
    c["chose"] = auto["dynamic_method"].values == "frequency"
    c["auto_err"] = np.maximum(
        np.abs(auto["tension_max"].values / tmax - 1.0),
        np.abs(auto["tension_min"].values / tmin - 1.0),
    )
    return c


def figs2_5(out: Path) -> None:
    auto, time_ = (
        run_text(out, "figs2-5-auto", figs_text("auto")),
        run_text(out, "figs2-5-time", figs_text("time")),
    )
    rows = frequency_answers(CONFIG.read_text())
    defaults = AutoSettings()
    c = compare(auto, time_, rows)
    err, ratio, sag, chose = c["err"], c["ratio"], c["sag"], c["chose"]
    summary = {
        "cases": int(chose.size),
        "auto_chose_frequency": int(np.count_nonzero(chose)),
        "largest_error_where_frequency_chosen": float(np.max(c["auto_err"][chose]))
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
            fd = c["fmax" if var == "tension_max" else "fmin"][k]
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
    print(json.dumps({k: summary[k] for k in list(summary)[:3]}))


def chain(out: Path) -> None:
    auto = run_text(out, "chain-auto", chain_text("auto"))
    time_ = run_text(out, "chain-time", chain_text("time"))
    rows = frequency_answers(chain_text("auto"))
    defaults = AutoSettings()
    c = compare(auto, time_, rows)
    chose = c["chose"]
    amps, f = time_["amplitude"].values, time_["frequency"].values
    reasons = auto["dynamic_method_reason"].values.astype(str)
    cases = [
        {
            "amplitude": float(amps[i]),
            "frequency": float(f[j]),
            "time_max": float(time_["tension_max"].values[i, j]),
            "time_min": float(time_["tension_min"].values[i, j]),
            "frequency_max": float(c["fmax"][i, j]),
            "frequency_min": float(c["fmin"][i, j]),
            "diff_max": round(float(c["d_max"][i, j]), 5),
            "diff_min": round(float(c["d_min"][i, j]), 5),
            "min_tension_ratio": round(float(c["ratio"][i, j]), 4),
            "amplitude_sag_ratio": round(float(c["sag"][i, j]), 5),
            "touchdown_travel": round(float(c["travel"][i, j]), 5),
            "auto": str(auto["dynamic_method"].values[i, j]),
            "auto_reason": reasons[i, j],
            "time_steady": int(time_["steady_converged"].values[i, j]),
        }
        for i in range(amps.size)
        for j in range(f.size)
    ]
    summary = {
        "cases": int(chose.size),
        "auto_chose_frequency": int(np.count_nonzero(chose)),
        "largest_error_where_frequency_chosen": float(np.max(c["auto_err"][chose]))
        if chose.any()
        else None,
        "thresholds": defaults.model_dump(),
        "cases_table": cases,
    }
    (HERE / "auto-study-chain.json").write_text(json.dumps(summary, indent=1))

    fig, axes = plt.subplots(3, 3, figsize=(15, 12))
    for k, ax in enumerate(axes.flat[: amps.size]):
        for var, style in (("tension_max", "-"), ("tension_min", "--")):
            ax.plot(f, time_[var].values[k] / 1e3, style, color="k", lw=1, label=f"time {var[8:]}")
            fd = c["fmax" if var == "tension_max" else "fmin"][k]
            ax.plot(f, fd / 1e3, style, color="C0", lw=1, label=f"frequency {var[8:]}")
            a = auto[var].values[k] / 1e3
            ax.plot(f[chose[k]], a[chose[k]], "o", color="C0", ms=4)
            ax.plot(f[~chose[k]], a[~chose[k]], "o", mfc="none", color="C3", ms=5)
        ax.set_xscale("log")
        ax.set_title(
            f"chain, surge {amps[k]:g} m (auto: filled = frequency, open = time)", fontsize=9
        )
        ax.set_xlabel("excitation frequency [Hz]")
        ax.set_ylabel("fairlead tension [kN]")
        ax.grid(alpha=0.3, which="both")
        if k == 0:
            ax.legend(fontsize=7)
    err = 100 * c["err"].ravel()
    panels = (
        ("travel", "estimated touchdown travel / line length [-]", defaults.max_touchdown_travel),
        ("ratio", "min / static tension along the line [-]", defaults.min_tension_ratio),
        ("sag", "largest displacement amplitude / sag [-]", defaults.max_amplitude_sag_ratio),
    )
    for ax, (key, label, threshold) in zip(axes.flat[amps.size :], panels, strict=True):
        x = c[key].ravel()
        ch = chose.ravel()
        sc = ax.scatter(
            x[ch],
            err[ch],
            c=np.log10(np.repeat(amps, f.size))[ch],
            marker="o",
            s=22,
            vmin=np.log10(amps.min()),
            vmax=np.log10(amps.max()),
            cmap="viridis",
            label="auto chose frequency",
        )
        ax.scatter(
            x[~ch],
            err[~ch],
            c=np.log10(np.repeat(amps, f.size))[~ch],
            marker="^",
            s=22,
            vmin=np.log10(amps.min()),
            vmax=np.log10(amps.max()),
            cmap="viridis",
            label="auto chose time",
        )
        ax.axvline(threshold, color="C3", lw=1, label="default threshold")
        if key == "travel":
            ax.axvline(0.01, color="C3", lw=0.8, ls="--", label="former default 0.01")
            ax.set_xscale("log")
        ax.axhline(2.0, color="k", lw=0.8, ls=":", label="2 %")
        ax.set_xlabel(label)
        ax.set_ylabel("frequency vs time domain, max |dT| / T [%]")
        ax.set_yscale("log")
        ax.grid(alpha=0.3, which="both")
        if key == "travel":
            ax.legend(fontsize=7)
    fig.colorbar(sc, ax=axes.flat[-1], label="log10 amplitude [m]")
    largest = summary["largest_error_where_frequency_chosen"]
    fig.suptitle(
        f"method auto on the chain mooring ({chose.size} cases): frequency chosen for "
        f"{summary['auto_chose_frequency']}, largest max/min difference to the time domain "
        f"there {100 * (largest or 0):.2f} % (red lines: default thresholds)",
        fontsize=10,
    )
    fig.tight_layout()
    fig.savefig(HERE / "auto-vs-time-chain.png", dpi=110)
    print(json.dumps({k: summary[k] for k in list(summary)[:3]}))


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if a not in ("figs2-5", "chain")]
    which = [a for a in sys.argv[1:] if a in ("figs2-5", "chain")] or ["figs2-5", "chain"]
    out_dir = Path(args[0]) if args else REPO / "results" / "auto-study"
    out_dir.mkdir(parents=True, exist_ok=True)
    if "figs2-5" in which:
        figs2_5(out_dir)
    if "chain" in which:
        chain(out_dir)
