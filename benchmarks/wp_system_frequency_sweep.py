"""A system's frequency domain against its time domain over a sweep of frequency (issue
24's "the frequency domain at least 100x faster per case than our time domain on a
50-case sweep of frequency"): MoorPy's case8 (``configs/system-case8-surge.yaml``, the
spar with three bridled polyester legs) surged 2 m at 50 frequencies from 0.02 to 0.5 Hz,
20 elements a line, the same study run by ``method: frequency`` and by ``method: time``
(each at its default settings) through the command line.

- Time: CPU time (``time.process_time``; the machine may be shared) of the whole run
  (reading, validation, the 50 cases' statics, model and dynamics, the netCDF write) over
  50, medians of repeated runs in one process with the analyses' caches emptied before
  each (:func:`bench_system_frequency.pipeline`: everything a user's run pays but the
  interpreter's start and the loading of the compiled kernels); the ratio a case and
  the ratio of one more case (the 50-case run against a one-case run). Then both
  studies in fresh processes (``cablestudy run`` as a user types it), where the
  interpreter's start weighs on the frequency domain's total.
- Error: the largest |T - T_time| / T_time,max over the lines' maximum and minimum end
  tensions (both ends, every frequency; ``T_time,max`` the time domain's maximum at that
  end) against the time domain's own answer; the time domain is the reference (its
  error is written as 0). At 2 m of surge and the higher frequencies the legs go slack
  in the time domain and the linear answer's minimum falls below zero, outside the
  frequency domain's validity (``method: auto`` sends such cases to the time domain);
  the notes give the error over the cases the linear answer keeps taut too.

Run: ``python benchmarks/wp_system_frequency_sweep.py [--quick]``.
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import xarray as xr

from cablestudy.bench import WorkPrecision

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from bench_system_frequency import ROOT, pipeline  # noqa: E402

ELEMENTS = 20
CASES = 50
TARGET = 100.0
KEYS = ("tension_max_a", "tension_min_a", "tension_max_b", "tension_min_b")


def _error(ours: xr.Dataset, ref: xr.Dataset, taut: bool = False) -> float:
    """Largest |T - T_ref| / T_max,ref over ``KEYS``, lines and frequencies (``T_max,ref``
    the reference's largest tension at that end of that line and case); with ``taut``
    only over the cases whose linear answer keeps every end tension above zero (where
    the frequency domain is inside its own validity)."""
    keep = np.ones(ours["tension_min_a"].shape[0], dtype=bool)
    if taut:
        keep = ((ours["tension_min_a"] > 0) & (ours["tension_min_b"] > 0)).values.all(axis=-1)
    if not keep.any():
        return float("nan")
    err = 0.0
    for k in KEYS:
        scale = ref[f"tension_max_{k[-1]}"].values[keep]
        err = max(err, float(np.max(np.abs(ours[k].values[keep] - ref[k].values[keep]) / scale)))
    return err


def _fresh_cpu(config: Path, out: Path) -> float:
    """CPU time [s] of a fresh ``cablestudy run`` of ``config`` (the child's user + system)."""
    import resource

    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    cli = [sys.executable, "-m", "cablestudy", "run", str(config), "--out", str(out)]
    subprocess.run([*cli, "--no-cache", "--no-progress"], check=True, capture_output=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def run(quick: bool = False) -> WorkPrecision:
    wp = WorkPrecision(
        name="system_frequency_sweep",
        title=f"case8 surged 2 m at {CASES} frequencies 0.02-0.5 Hz: frequency against time domain",
        error_name="largest |T - T_time| / T_time,max of the lines' max/min end tensions",
        time_name="CPU time a case (the whole run over the cases) [s]",
    )
    repeats = 1 if quick else 3
    with tempfile.TemporaryDirectory() as tmp:
        keep = Path(tmp)
        p = pipeline(ELEMENTS, CASES, repeats, keep=keep)
        with xr.open_dataset(keep / "frequency.nc") as f, xr.open_dataset(keep / "time.nc") as t:
            f, t = f.load(), t.load()
            err, err_taut = _error(f, t), _error(f, t, taut=True)
            taut = int(((f["tension_min_a"] > 0) & (f["tension_min_b"] > 0)).values.all(-1).sum())
            ok_f = int((f["status"].values == 0).sum())
            ok_t = int((t["status"].values == 0).sum())
        setting = f"{ELEMENTS} elements a line, {CASES} cases"
        ratio, marginal = p["time"] / p["frequency"], p["time_marginal"] / p["frequency_marginal"]
        # no peer curve: the time domain is the reference of the error, not a peer at
        # equal error; the ratio a case is the measure
        label = f"frequency domain (method: frequency), time / frequency = {ratio:.0f} a case"
        wp.curve(label).add(setting, p["frequency"], err)
        wp.curve("time domain (method: time), the reference").add(setting, p["time"], 0.0)
        wp.notes.append(
            f"through the command line in process (caches emptied, CPU medians of {repeats}): "
            f"frequency {p['frequency'] * 1e3:.2f} ms a case ({p['frequency'] * CASES * 1e3:.0f} "
            f"ms the {CASES}-case run), time {p['time'] * 1e3:.1f} ms a case: time / frequency = "
            f"{ratio:.1f} (the issue's target: {TARGET:.0f}, "
            f"{'met' if ratio >= TARGET else 'not met'}); one more case: frequency "
            f"{p['frequency_marginal'] * 1e3:.2f} ms, time {p['time_marginal'] * 1e3:.1f} ms: "
            f"{marginal:.0f}; a study of one case: frequency {p['frequency_one'] * 1e3:.1f} ms, "
            f"time {p['time_one'] * 1e3:.1f} ms; cases at status 0: frequency {ok_f}, time "
            f"{ok_t} of {CASES}; cases run as arrays: {p['frequency_arrays']:.0f}; error "
            f"against the time domain {err:.1e} of T_max over all cases, {err_taut:.1e} over "
            f"the {taut} whose linear answer stays taut"
        )
        if quick:
            return wp
        text = (ROOT / "configs" / "system-case8-surge.yaml").read_text()
        head = text[: text.index("  dynamic:")]
        freqs = ", ".join(f"{f:.6g}" for f in np.linspace(0.02, 0.5, CASES))
        cpu = {}
        for method in ("frequency", "time"):
            cfg = keep / f"fresh-{method}.yaml"
            cfg.write_text(
                head + "  dynamic:\n"
                "    excitation: {body: body1, dof: surge, amplitude: 2.0, frequency: 0.1}\n"
                f"    method: {method}\n    elements: {ELEMENTS}\n"
                f"sweep:\n  analysis.dynamic.excitation.frequency: [{freqs}]\n"
            )
            _fresh_cpu(cfg, keep / f"fresh-{method}")  # bytecode and kernels loaded once
            t0 = time.perf_counter()
            cpu[method] = statistics.median(
                _fresh_cpu(cfg, keep / f"fresh-{method}") for _ in range(3)
            )
            wall = (time.perf_counter() - t0) / 3
            cpu[f"{method}_wall"] = wall
        wp.notes.append(
            f"fresh processes (`cablestudy run` of the {CASES}-case study, the default "
            f"scheduler; CPU of the process, medians of 3): frequency {cpu['frequency']:.2f} s "
            f"(wall {cpu['frequency_wall']:.2f} s), time {cpu['time']:.2f} s (wall "
            f"{cpu['time_wall']:.2f} s): time / frequency = {cpu['time'] / cpu['frequency']:.1f}; "
            "the interpreter's start, imports and the kernels' loading are most of the "
            "frequency domain's run"
        )
    return wp


if __name__ == "__main__":
    result = run(quick="--quick" in sys.argv)
    print("\n".join(result.summary_rows()))
    print("\n".join(result.notes))
