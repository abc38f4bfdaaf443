"""The first sweep a mooring engineer runs (issue 20): a studless chain (300 m, 76 mm,
126 kg/m) from an anchor on a flat seabed in 100 m of water to a fairlead 10 m below
the surface, seabed friction 0.5, 200 fairlead offsets (215-275 m, every one with a laid
part, some of it slack) x 100 axial stiffnesses (1e8-2e9 N), 20 output nodes: 20,000
lines through ``cablestudy run`` in a fresh process (start-up, kernel load, validation,
solve and netCDF write included; the study written as a user writes it: no ``method``
key, defaults left out), against MoorPy's ``catenary`` with ``CB = 0.5`` on the same
20,000 lines in a plain Python loop, timed in the same run.

"Error" is the largest difference of the fairlead tension between the two codes,
relative to that tension, over the cases both solve (MoorPy at ``Tol=1e-10``, so that
its own convergence does not set the agreement). Our time is the median of 3 fresh
processes after one untimed run; MoorPy's loop runs once (7-15 s on this machine,
depending on its load).

The untimed first run stands for the installation: it writes the package's bytecode and
loads (or compiles) the numba kernels, as ``pip install`` and the issue's compile-at-
install step do for a user. The timed runs keep the bytecode even where the calling
environment sets ``PYTHONDONTWRITEBYTECODE`` (a user's installed package has it); the
notes say which.
"""

from __future__ import annotations

import math
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from cablestudy.bench import WorkPrecision

DEPTH, FAIRLEAD, L, MASS, DIAMETER, MU = 100.0, -10.0, 300.0, 126.0, 0.076, 0.5
OFFSETS = (215.0, 275.0)
STIFFNESS = (1.0e8, 2.0e9)

STUDY = """\
name: {name}
environment: {{fluid: water, depth: {depth}, seabed: {{friction: {mu}}}}}
line:
  segments:
    - {{length: {L}, diameter: {d}, mass_per_length: {m}, axial_stiffness: 5.0e8}}
ends:
  a: {{kind: fixed, position: [0.0, 0.0, {za}]}}
  b: {{kind: fixed, position: [250.0, 0.0, {zb}]}}
analysis:
  static: {{nodes: 20}}
sweep:
  ends.b.position.0: {{start: {x0}, stop: {x1}, num: {n_x}, name: offset}}
  line.segments.0.axial_stiffness: {{start: {e0}, stop: {e1}, num: {n_ea}}}
"""


def study(path: Path, name: str, n_x: int, n_ea: int) -> Path:
    path.write_text(
        STUDY.format(
            name=name,
            depth=DEPTH,
            mu=MU,
            L=L,
            d=DIAMETER,
            m=MASS,
            za=-DEPTH,
            zb=FAIRLEAD,
            x0=OFFSETS[0],
            x1=OFFSETS[1],
            n_x=n_x,
            e0=STIFFNESS[0],
            e1=STIFFNESS[1],
            n_ea=n_ea,
        )
    )
    return path


def _env() -> dict[str, str]:
    """The calling environment with this checkout first on the path, bytecode kept."""
    env = dict(os.environ)
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    root = str(Path(__file__).resolve().parents[1])
    env["PYTHONPATH"] = os.pathsep.join(p for p in (root, env.get("PYTHONPATH", "")) if p)
    return env


def cli_run(config: Path, out: Path) -> tuple[float, float, float]:
    """`cablestudy run` end to end in a fresh process: wall time [s], peak RSS [MB] and
    CPU time (user + system) [s] (as :func:`wp_sweep.cli_run`, with :func:`_env`)."""
    cli = [sys.executable, "-m", "cablestudy", "run", str(config), "--out", str(out)]
    cli += ["--no-cache", "--no-progress", "--scheduler", "synchronous"]
    timer = Path("/usr/bin/time")
    with tempfile.NamedTemporaryFile("r", suffix=".rss") as fh:
        args = [str(timer), "-f", "%M %U %S", "-o", fh.name, *cli] if timer.exists() else cli
        t0 = time.perf_counter()
        proc = subprocess.run(args, env=_env(), capture_output=True, check=False)
        wall = time.perf_counter() - t0
        if proc.returncode != 0:
            raise RuntimeError(f"{' '.join(cli)} failed: {proc.stderr.decode()[-2000:]}")
        rss, cpu = math.nan, math.nan
        if timer.exists():
            kb, user, system = fh.read().split()[-3:]
            rss, cpu = float(kb) / 1024, float(user) + float(system)
    return wall, rss, cpu


def ours(path: Path) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    import xarray as xr

    with xr.open_dataset(path) as ds:
        return (
            ds["offset"].values,
            ds["axial_stiffness"].values,
            ds["tension_b"].values,
            ds["status"].values,
        )


def submerged_weight() -> float:
    """[N/m] as the study computes it (mass minus displaced sea water, g = 9.80665)."""
    return (MASS - 1025.0 * math.pi * DIAMETER**2 / 4.0) * 9.80665


def moorpy_loop(
    offsets: np.ndarray, stiffnesses: np.ndarray
) -> tuple[float, float, np.ndarray] | None:
    """Time MoorPy's catenary with seabed friction over every (offset, EA) pair:
    (wall seconds, CPU seconds, fairlead tensions)."""
    try:
        from moorpy.Catenary import catenary
    except ImportError:
        return None
    w = submerged_weight()
    h = FAIRLEAD + DEPTH
    out = np.full((len(offsets), len(stiffnesses)), np.nan)
    t0, c0 = time.perf_counter(), time.process_time()
    for i, x in enumerate(offsets):
        for j, ea in enumerate(stiffnesses):
            try:
                _, _, fbh, fbv, _ = catenary(
                    float(x), h, L, float(ea), w, CB=MU, Tol=1e-10, MaxIter=200
                )
            except Exception:  # noqa: BLE001, S112 - a MoorPy failure is a missing point
                continue
            out[i, j] = math.hypot(fbh, fbv)
    return time.perf_counter() - t0, time.process_time() - c0, out


def run(quick: bool = False) -> WorkPrecision:
    wp = WorkPrecision(
        name="sweep_seabed_20k",
        title="20,000-case seabed sweep with friction 0.5 (200 offsets x 100 EA, 20 nodes)",
        error_name="largest fairlead-tension difference between the codes / tension",
        time_name="wall time per case, end to end [s]",
    )
    dont = bool(os.environ.get("PYTHONDONTWRITEBYTECODE"))
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        cfg = study(folder / "seabed20k.yaml", "seabed20k", 200, 100)
        first = cli_run(cfg, folder / "out")[0]  # the installation's share (see above)
        runs = [cli_run(cfg, folder / "out") for _ in range(1 if quick else 3)]
        wall = statistics.median(r[0] for r in runs)
        rss = max(r[1] for r in runs)
        cpu = statistics.median(r[2] for r in runs)
        offset, ea, tension, status = ours(folder / "out" / "seabed20k.nc")
        n = tension.size
        peer = moorpy_loop(offset, ea)
        if peer is None:
            err = math.nan
            wp.notes.append("MoorPy not installed (pip install '.[peers]'): its loop skipped")
        else:
            t_peer, cpu_peer, t_moorpy = peer
            both = np.isfinite(t_moorpy) & np.isfinite(tension)
            err = float(np.max(np.abs(t_moorpy[both] - tension[both]) / tension[both]))
            wp.curve("MoorPy catenary CB=0.5, Python loop", peer=True).add(
                f"{n} cases, Tol=1e-10", t_peer / n, err
            )
            wp.notes.append(
                f"20,000 cases on the seabed with friction 0.5: `cablestudy run` {wall:.2f} s "
                f"end to end (median of {len(runs)} fresh processes: "
                f"{', '.join(f'{r[0]:.2f}' for r in runs)} s, after an untimed first run "
                f"of {first:.2f} s; bytecode kept"
                f"{' (PYTHONDONTWRITEBYTECODE set here, dropped for these runs)' if dont else ''}"
                f"; peak RSS {rss:.0f} MB; "
                f"{int(np.sum(status != 0))} failed) against the MoorPy loop {t_peer:.2f} s: "
                f"{wall / t_peer:.2f} x its time (the issue's target: 0.25 x); CPU time "
                f"(user + system, less sensitive to the machine's load) {cpu:.2f} s against "
                f"{cpu_peer:.2f} s: {cpu / cpu_peer:.2f} x; "
                f"{int(both.sum())} cases both solve agree to {err:.1e} of the fairlead tension"
            )
        wp.curve("cablestudy run (array path, contact kernel)").add(
            f"{n} cases, 20 nodes", wall / n, err
        )
    return wp


if __name__ == "__main__":
    got = run(quick="--quick" in sys.argv)
    print("\n".join(got.summary_rows()))
    print("\n".join(got.notes))
