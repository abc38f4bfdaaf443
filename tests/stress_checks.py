"""Running random studies and checking them independently of the solvers (the stress
helper's harness; the studies come from :mod:`tests.stress_studies`).

:func:`run_study` runs a study through the command line (``cablestudy run STUDY --out
DIR``, or :func:`cablestudy.cli.main` in this process), :func:`check_run` checks the run
and every case of its dataset against what a user can recompute from the written
outputs, :func:`swapped` and :func:`check_swap` the same study with its ends swapped.
The checks are listed in :mod:`tests.stress_studies`.
"""

from __future__ import annotations

import math
import os
import re
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import yaml

from tests.stress_studies import GRAVITY, WATER, Meta, _round, _weight

# --------------------------------------------------------------------------- running


@dataclass
class RunResult:
    code: int
    stdout: str
    stderr: str
    seconds: float
    nc: Path | None


def run_study(
    study: dict, workdir: Path, timeout: float = 300.0, in_process: bool = False
) -> RunResult:
    """``cablestudy run STUDY.yaml --out DIR`` in a fresh process (as a user runs it), or
    with ``in_process`` through :func:`cablestudy.cli.main` in this one (the test: no
    start-up per study), its output captured, an escaping exception reported as the
    traceback a user would see and numpy's RuntimeWarnings as printed."""
    workdir.mkdir(parents=True, exist_ok=True)
    cfg = workdir / f"{study['name']}.yaml"
    cfg.write_text(yaml.safe_dump(study, sort_keys=False))
    if in_process:
        return _run_in_process(cfg, workdir, study["name"])
    env = dict(os.environ)
    env["PYTHONWARNINGS"] = "default"  # numpy's RuntimeWarnings would show
    t0 = time.perf_counter()
    try:
        p = subprocess.run(
            [
                sys.executable,
                "-m",
                "cablestudy.cli",
                "run",
                str(cfg),
                "--out",
                str(workdir),
                "--no-cache",
                "--scheduler",
                "synchronous",
                "--no-progress",
            ],
            capture_output=True,
            text=True,
            env=env,
            timeout=timeout,
        )
        code, out, err = p.returncode, p.stdout, p.stderr
    except subprocess.TimeoutExpired as e:
        code, out, err = -9, str(e.stdout or ""), f"timeout after {timeout} s"
    dt = time.perf_counter() - t0
    nc = workdir / f"{study['name']}.nc"
    return RunResult(code, out, err, dt, nc if nc.exists() else None)


def _run_in_process(cfg: Path, workdir: Path, name: str) -> RunResult:
    import contextlib
    import io
    import traceback
    import warnings

    from cablestudy.cli import main

    out, err = io.StringIO(), io.StringIO()
    t0 = time.perf_counter()
    with (
        warnings.catch_warnings(record=True) as caught,
        contextlib.redirect_stdout(out),
        contextlib.redirect_stderr(err),
    ):
        warnings.simplefilter("always")
        try:
            code = int(
                main(
                    [
                        "run",
                        str(cfg),
                        "--out",
                        str(workdir),
                        "--no-cache",
                        "--scheduler",
                        "synchronous",
                        "--no-progress",
                    ]
                )
                or 0
            )
        except SystemExit as e:
            code = int(e.code or 0)
        except BaseException:  # what a user would see: a traceback, exit 1
            err.write(traceback.format_exc())
            code = 1
    for w in caught:
        if issubclass(w.category, RuntimeWarning):
            err.write(f"{w.filename}:{w.lineno}: RuntimeWarning: {w.message}\n")
    dt = time.perf_counter() - t0
    nc = workdir / f"{name}.nc"
    return RunResult(code, out.getvalue(), err.getvalue(), dt, nc if nc.exists() else None)


# --------------------------------------------------------------------------- checks


def _cases(ds: Any) -> list[dict]:
    """Each case as a dict of indexers over the sweep dims."""
    dims = [d for d in ds["status"].dims]
    if not dims:
        return [{}]
    idx = np.ndindex(*[ds.sizes[d] for d in dims])
    return [dict(zip(dims, i, strict=True)) for i in idx]


def _f(ds: Any, name: str, case: dict) -> np.ndarray | None:
    if name not in ds:
        return None
    v = ds[name].isel({k: v for k, v in case.items() if k in ds[name].dims})
    return np.asarray(v.values, dtype=float)


def _study_case(study: dict, ds: Any, case: dict, meta: Meta) -> dict:
    """The study with this case's swept value set (span or current speed)."""
    import copy

    st = copy.deepcopy(study)
    if meta.sweep_dim == "span":
        st["ends"]["b"]["position"][0] = float(ds["span"].values[case["span"]])
    elif meta.sweep_dim == "surface_speed":
        st["environment"]["current"][0]["speed"] = float(
            ds["surface_speed"].values[case["surface_speed"]]
        )
    elif meta.sweep_dim == "surge":
        st["bodies"]["hull"]["position"][0] = float(ds["surge"].values[case["surge"]])
    return st


def check_run(study: dict, meta: Meta, res: RunResult) -> list[tuple[str, str]]:
    out: list[tuple[str, str]] = []
    text = res.stdout + res.stderr
    if "Traceback" in text:
        out.append(("traceback", text[-1500:]))
    if "RuntimeWarning" in text:
        line = next(ln for ln in text.splitlines() if "RuntimeWarning" in ln)
        out.append(("runtime_warning", line))
    if res.code == 2:
        if meta.expect_refusal and meta.expect_refusal in text:
            return out
        # a refusal must name the field (a dotted path and the value, docs/guide/cli.md)
        named = re.search(r"^\S*:\d+: [a-z_]+(\.[a-z_0-9<>]+)*:", res.stderr, re.M)
        out.append(("info_refused" if named else "refused_unnamed", res.stderr.strip()[-600:]))
        return out
    if meta.expect_refusal:
        out.append(
            ("not_refused", f"{meta.expect_refusal} under method {meta.method}: exit {res.code}")
        )
    if res.code not in (0, 3):
        out.append(("exit_code", f"exit {res.code}: {res.stderr.strip()[-800:]}"))
        return out
    if res.nc is None:
        out.append(("no_dataset", f"exit {res.code} and no dataset"))
        return out
    import xarray as xr

    with xr.open_dataset(res.nc) as ds:
        ds.load()
    n_ok = int((ds["status"].values == 0).sum())
    if res.code == 0 and n_ok == 0 and not np.any(ds["status"].values == 10):
        out.append(("exit_code", "exit 0 with no case of status 0"))
    if res.code == 3 and n_ok > 0:
        out.append(("exit_code", "exit 3 with a case of status 0"))
    for case in _cases(ds):
        st = _study_case(study, ds, case, meta)
        for kind, text in check_case(ds, case, st, meta):
            out.append((kind, f"case {case}: {text}"))
    return out


def _msg(ds: Any, name: str, case: dict) -> str:
    if name not in ds:
        return ""
    v = ds[name].isel({k: v for k, v in case.items() if k in ds[name].dims}).values
    return str(v.item() if hasattr(v, "item") else v)


STATIC_VARS = ("x", "y", "z", "tension", "force_a", "force_b", "tension_a", "tension_b")
DYN_VARS = ("tension_max", "tension_min", "tension_mean")


def check_case(ds: Any, case: dict, study: dict, meta: Meta) -> list[tuple[str, str]]:
    out: list[tuple[str, str]] = []
    status = int(ds["status"].isel(case).values)
    sstat = int(ds["static_status"].isel(case).values) if "static_status" in ds else status
    dstat = int(ds["dynamic_status"].isel(case).values) if "dynamic_status" in ds else None
    msg = _msg(ds, "message", case)
    if status != 0 and not msg.strip():
        out.append(("empty_message", f"status {status} and no message"))
    if status == 0 and msg.strip():
        out.append(("message_when_ok", msg[:300]))
    if re.search(r"\bnan\b|\binf\b", msg, re.I) and status != 0:
        out.append(("nan_in_message", msg[:300]))
    if sstat not in (0, 10, 11):
        for v in STATIC_VARS:
            a = _f(ds, v, case)
            if a is not None and np.any(np.isfinite(a)):
                out.append(("number_in_failed", f"static_status {sstat} but {v} has numbers"))
                break
    if sstat in (0, 10):
        for v in STATIC_VARS:
            a = _f(ds, v, case)
            if a is not None and not np.all(np.isfinite(a)):
                out.append(("nan_when_ok", f"static_status {sstat} and {v} not finite"))
                break
        else:
            if sstat == 0:
                out += _check_statics(ds, case, study, meta)
    if dstat is not None:
        vals = {v: _f(ds, v, case) for v in DYN_VARS}
        if dstat == 0:
            if any(a is None or not np.all(np.isfinite(a)) for a in vals.values()):
                out.append(
                    ("nan_when_ok", "dynamic_status 0 with a non-finite tension_max/min/mean")
                )
            else:
                tmax, tmean, tmin = vals["tension_max"], vals["tension_mean"], vals["tension_min"]
                tol = 1e-9 * np.maximum(np.abs(tmax), 1.0)
                if not (np.all(tmax + tol >= tmean) and np.all(tmean >= tmin - tol)):
                    out.append(("dyn_order", f"tension max {tmax}, mean {tmean}, min {tmin}"))
        else:
            for v, a in vals.items():
                if a is not None and np.any(np.isfinite(a)):
                    out.append(("number_in_failed", f"dynamic_status {dstat} but {v} = {a}"))
                    break
            if dstat != 5 and sstat == 0:
                t = _f(ds, "tension", case)
                if t is None or not np.all(np.isfinite(t)):
                    out.append(
                        ("statics_lost", f"dynamic_status {dstat}: the statics are not kept")
                    )
    return out


def _check_statics(ds: Any, case: dict, study: dict, meta: Meta) -> list[tuple[str, str]]:
    if meta.kind == "system":
        return _check_system(ds, case, study, meta)
    out: list[tuple[str, str]] = []
    x, y, z = (_f(ds, c, case) for c in "xyz")
    t = _f(ds, "tension", case)
    s = _f(ds, "arc_length", case) if "arc_length" in ds else np.asarray(ds["s"].values, float)
    segs = study["line"]["segments"]
    total = sum(sg["length"] for sg in segs)
    scale = max(total, 1.0)
    pos = np.stack([x, y, z], axis=-1)
    # end positions
    ea = study["ends"]["a"]
    eb = study["ends"]["b"]
    tol_pos = 1e-5 * scale + 1e-6
    if ea["kind"] == "fixed" and np.linalg.norm(pos[0] - np.array(ea["position"])) > tol_pos:
        out.append(("end_position", f"A at {pos[0]} not {ea['position']}"))
    if eb["kind"] == "fixed" and np.linalg.norm(pos[-1] - np.array(eb["position"])) > tol_pos:
        out.append(("end_position", f"B at {pos[-1]} not {eb['position']}"))
    if eb["kind"] == "mooring" and abs(pos[-1, 2] - eb["z"]) > tol_pos:
        out.append(("end_position", f"B at z {pos[-1, 2]} not {eb['z']}"))
    # tension >= 0 without bending
    tmax = float(np.max(np.abs(t))) if t.size else 0.0
    if not meta.bending and np.min(t) < -1e-6 * max(tmax, 1.0):
        out.append(("negative_tension", f"min tension {np.min(t):.6g} N (max {tmax:.6g})"))
    # stretched node spacing no longer than the stretched arc between them
    bounds = np.cumsum([0.0] + [sg["length"] for sg in segs])
    mid = 0.5 * (s[1:] + s[:-1])
    ea_all = np.array([sg["axial_stiffness"] for sg in segs])
    i0 = np.clip(np.searchsorted(bounds, s[:-1], side="right") - 1, 0, len(segs) - 1)
    i1 = np.clip(np.searchsorted(bounds, s[1:], side="left") - 1, 0, len(segs) - 1)
    ea_s = np.array([ea_all[a : b + 1].min() for a, b in zip(i0, np.maximum(i0, i1), strict=True)])
    del mid
    ds_ = np.diff(s)
    chord = np.linalg.norm(np.diff(pos, axis=0), axis=1)
    tpair = np.maximum(np.abs(t[1:]), np.abs(t[:-1]))
    if meta.method == "discrete":
        # its node tensions are the neighbouring elements' mean: an element's own may
        # exceed both of its nodes' by one element's load (weight, or an attachment
        # lumped on a node, seed 567)
        rho = meta.rho
        w_max = max(abs(_weight(sg, rho)) for sg in segs)
        att = [
            np.linalg.norm(a.get("force", [0.0, 0.0, 0.0]))
            + GRAVITY * (a.get("mass", 0.0) + rho * a.get("volume", 0.0))
            for a in study["line"].get("attachments", [])
        ]
        tpair = tpair + w_max * ds_ + max(att, default=0.0)
    arc_max = ds_ * (1.0 + tpair / ea_s)
    # the linear law between the two nodes' tensions bounds the stretched length; a
    # relative 1e-6 for the solver's tolerance and rounding (the nodes' positions are
    # exact to the Newton tolerance, 1e-9 relative, times the line's length)
    bad = chord > arc_max * (1 + 1e-6) + 1e-7 * scale
    if np.any(bad) and not meta.bending:
        i = int(np.argmax(chord - arc_max))
        out.append(
            ("stretch", f"nodes {i}-{i + 1}: chord {chord[i]:.9g} > stretched arc {arc_max[i]:.9g}")
        )
    # whole-line balance (known loads: no current)
    if not meta.current:
        out += _check_balance(ds, case, study, meta, s, pos, t)
    return out


def _seg_weights(study: dict, rho: float) -> tuple[np.ndarray, np.ndarray]:
    segs = study["line"]["segments"]
    bounds = np.cumsum([0.0] + [sg["length"] for sg in segs])
    return bounds, np.array([_weight(sg, rho) for sg in segs])


def _check_balance(ds, case, study, meta, s, pos, t) -> list[tuple[str, str]]:
    out: list[tuple[str, str]] = []
    fa = _f(ds, "force_a", case)
    fb = _f(ds, "force_b", case)
    if fa is None or fb is None:
        return out
    rho = meta.rho
    bounds, w = _seg_weights(study, rho)
    load = np.zeros(3)
    load[2] -= float(np.sum(w * np.diff(bounds)))
    for att in study["line"].get("attachments", []):
        load += np.asarray(att.get("force", [0.0, 0.0, 0.0]), float)
        load[2] -= att.get("mass", 0.0) * GRAVITY
        load[2] += rho * att.get("volume", 0.0) * GRAVITY
    # the seabed's reaction on the laid part (nodes on the flat seabed)
    on_bed = np.zeros(len(s), bool)
    if meta.depth is not None:
        gap = pos[:, 2] + meta.depth
        if meta.slope:
            return out  # the bed plane's reaction is not vertical: not checked
        on_bed = gap < 1e-6 * max(meta.depth, 1.0) + 1e-4
    # weight of the laid part, integrated by the trapezoidal rule on the nodes
    wn = w[np.clip(np.searchsorted(bounds, s, side="right") - 1, 0, len(w) - 1)]
    laid_w = 0.0
    for i in range(len(s) - 1):
        if on_bed[i] and on_bed[i + 1]:
            laid_w += 0.5 * (wn[i] + wn[i + 1]) * (s[i + 1] - s[i])
    # the line's balance: -force_a - force_b + load + seabed reaction = 0
    resid = fa + fb - load
    ref = max(np.linalg.norm(fa), np.linalg.norm(fb), np.abs(load).max(), 1.0)
    # a node half on the seabed: the laid weight is known to one element's weight
    ds_max = float(np.max(np.diff(s))) if len(s) > 1 else 0.0
    touch = bool(on_bed.any())
    tol_z = 1e-6 * ref + (2 * float(np.max(np.abs(w))) * ds_max if touch else 0.0)
    if touch:
        resid_z = (
            resid[2] - laid_w
        )  # the bed pushes up the laid weight: fa_z + fb_z = load_z + laid
        if meta.attachments:
            return out  # an attachment on the bed: its weight is carried too
    else:
        resid_z = resid[2]
    if abs(resid_z) > tol_z:
        out.append(
            (
                "balance_z",
                f"vertical: force_a+force_b = {fa[2] + fb[2]:.9g} N, weight and loads "
                f"{load[2]:.9g} N, laid {laid_w:.6g} N (residual {resid_z:.3g}, tol {tol_z:.3g})",
            )
        )
    if not (touch and meta.friction > 0):
        rh = float(np.hypot(resid[0], resid[1]))
        if rh > 1e-6 * ref:
            out.append(
                (
                    "balance_h",
                    f"horizontal: force_a+force_b = {fa[:2] + fb[:2]} N, loads {load[:2]} "
                    f"(residual {rh:.3g} N, ref {ref:.3g})",
                )
            )
    # the tension's change between suspended nodes of one segment: dT = w0 dz / (1 + e)
    # (effective tension, still fluid; w0 per unstretched length): the trapezoidal rule
    # on 1 / (1 + e) over the interval errs by less than w0 |dz| |de| (e's change there)
    if not meta.attachments and not meta.bending:
        ea_n = np.array(
            [
                study["line"]["segments"][i]["axial_stiffness"]
                for i in np.clip(np.searchsorted(bounds, s, side="right") - 1, 0, len(w) - 1)
            ]
        )
        e = t / ea_n
        dz = np.diff(pos[:, 2])
        same = np.diff(np.clip(np.searchsorted(bounds, s, side="right") - 1, 0, len(w) - 1)) == 0
        susp = ~(on_bed[1:] | on_bed[:-1]) & same
        pred = wn[:-1] * dz * 0.5 * (1 / (1 + e[1:]) + 1 / (1 + e[:-1]))
        err = np.abs(np.diff(t) - pred)
        allow = np.abs(wn[:-1] * dz) * (np.abs(np.diff(e)) + 1e-6) + 1e-6 * ref
        if meta.method == "discrete":
            # element tensions averaged at the nodes: a node at a joint takes half of
            # the heavier neighbour's element (seed 715), so the heaviest element's weight
            allow = allow + float(np.max(np.abs(w))) * float(np.max(np.diff(s)))
        bad = susp & (err > allow)
        if np.any(bad):
            i = int(np.argmax(np.where(bad, err - allow, -np.inf)))
            out.append(
                (
                    "tension_gradient",
                    f"nodes {i}-{i + 1}: dT {t[i + 1] - t[i]:.9g} N, w dz/(1+e) "
                    f"{pred[i]:.9g} N (allowed {allow[i]:.3g})",
                )
            )
    # the end tensions are the end forces' magnitudes; elevation at the ends is the end
    # forces' direction (no point load or bending there)
    ta, tb = np.linalg.norm(fa), np.linalg.norm(fb)
    if abs(t[0] - ta) > 1e-6 * ref or abs(t[-1] - tb) > 1e-6 * ref:
        out.append(
            (
                "end_tension",
                f"tension at the ends {t[0]:.9g}, {t[-1]:.9g} N; |force_a|, |force_b| "
                f"{ta:.9g}, {tb:.9g} N",
            )
        )
    el = _f(ds, "elevation", case)
    if el is not None and not meta.bending and not touch and not meta.attachments:
        ela = math.atan2(fa[2], math.hypot(fa[0], fa[1]))
        elb = math.atan2(-fb[2], math.hypot(fb[0], fb[1]))
        d = max(abs(el[0] - ela), abs(el[-1] - elb))
        if d > 1e-2:
            out.append(
                (
                    "info_elevation_fd",
                    f"elevation at the ends {el[0]:.6g}, {el[-1]:.6g} rad; the end "
                    f"forces' {ela:.6g}, {elb:.6g} rad (nodes {len(s)})",
                )
            )
    return out


def _check_system(ds, case, study, meta) -> list[tuple[str, str]]:
    out: list[tuple[str, str]] = []
    names = [str(n) for n in ds["line"].values]
    fb = _f(ds, "force_b", case)
    t = _f(ds, "tension", case)
    if t is not None and np.nanmin(t) < -1e-6 * max(np.nanmax(np.abs(t)), 1.0):
        out.append(("negative_tension", f"system min tension {np.nanmin(t):.6g}"))
    # per line: ends at their points
    x, y, z = (_f(ds, c, case) for c in "xyz")
    for i, nm in enumerate(names):
        ln = study["lines"][nm]
        pa = study["points"][ln["a"]]
        if pa["kind"] == "fixed":
            p0 = np.array([x[i, 0], y[i, 0], z[i, 0]])
            if np.linalg.norm(p0 - np.array(pa["position"])) > 1e-5 * 1000:
                out.append(("end_position", f"line {nm} A at {p0} not {pa['position']}"))
    # a free body: its lines' force balances its weight and buoyancy
    body = study.get("bodies", {}).get("hull")
    if body is not None and body["kind"] == "free" and "body_force" in ds:
        bf = _f(ds, "body_force", case)
        net = bf[0, :3] + np.array([0.0, 0.0, (WATER * body["volume"] - body["mass"]) * GRAVITY])
        ref = max(float(np.nanmax(np.abs(fb))) if fb is not None else 1.0, 1.0)
        if np.linalg.norm(net) > 1e-5 * max(ref, body["mass"] * GRAVITY):
            out.append(
                (
                    "balance_body",
                    f"free body: lines' force {bf[0, :3]} N with weight and buoyancy "
                    f"leaves {net} N",
                )
            )
    # free hub: the lines' pull balances its weight
    if "hub" in study["points"] and fb is not None:
        hub = study["points"]["hub"]
        total = fb.sum(axis=0)  # the lines' forces on the hub
        total[2] -= hub.get("mass", 0.0) * GRAVITY
        total[2] += WATER * hub.get("volume", 0.0) * GRAVITY
        ref = max(float(np.abs(fb).max()), 1.0)
        if np.linalg.norm(total) > 1e-5 * ref:
            out.append(("balance_point", f"free point residual {total} N (ref {ref:.3g})"))
    return out


# --------------------------------------------------------------------------- symmetry


def swapped(study: dict) -> dict | None:
    """The same one-line study with its ends swapped (segments reversed, attachments at
    L - s), or None where that is not the same problem (a force or mooring end, an
    excitation, a current sweep is kept)."""
    import copy

    if (
        "line" not in study
        or study["ends"]["b"]["kind"] != "fixed"
        or "dynamic" in study["analysis"]
    ):
        return None
    st = copy.deepcopy(study)
    st["name"] = study["name"] + "-swapped"
    segs = st["line"]["segments"][::-1]
    st["line"]["segments"] = segs
    total = sum(sg["length"] for sg in segs)
    for att in st["line"].get("attachments", []):
        att["s"] = _round(total - att["s"], 12)
    st["ends"] = {"a": st["ends"]["b"], "b": st["ends"]["a"]}
    sw = st.get("sweep", {})
    if "ends.b.position.0" in sw:
        sw["ends.a.position.0"] = sw.pop("ends.b.position.0")
    return st


def check_swap(res1: RunResult, res2: RunResult, meta: Meta) -> list[tuple[str, str]]:
    """Swapping the ends changes nothing but the direction of s: same status, end forces
    exchanged, the tension profile reversed."""
    import xarray as xr

    if res1.nc is None or res2.nc is None:
        if (res1.nc is None) != (res2.nc is None):
            return [("swap_status", f"exit {res1.code} vs swapped {res2.code}")]
        return []
    with xr.open_dataset(res1.nc) as d1, xr.open_dataset(res2.nc) as d2:
        d1.load()
        d2.load()
    out: list[tuple[str, str]] = []
    for case in _cases(d1):
        s1 = int(d1["status"].isel(case).values)
        s2 = int(d2["status"].isel(case).values)
        if (s1 == 0) != (s2 == 0):
            out.append(
                (
                    "swap_status",
                    f"case {case}: status {s1} vs swapped {s2}: "
                    f"{_msg(d1, 'message', case)[:200]} | {_msg(d2, 'message', case)[:200]}",
                )
            )
            continue
        if s1 != 0:
            continue
        fa1, fb1 = _f(d1, "force_a", case), _f(d1, "force_b", case)
        fa2, fb2 = _f(d2, "force_a", case), _f(d2, "force_b", case)
        ref = max(np.abs(fa1).max(), np.abs(fb1).max(), 1.0)
        # the solvers' own tolerance (1e-9 relative) on both; 1e-6 of the force scale
        # leaves room for the different path the iteration takes from the other end
        tol = 1e-6 * ref if meta.method != "discrete" else 1e-4 * ref
        if np.abs(fa1 - fb2).max() > tol or np.abs(fb1 - fa2).max() > tol:
            out.append(
                ("swap_forces", f"case {case}: force_a {fa1}, force_b {fb1}; swapped {fa2}, {fb2}")
            )
        t1, t2 = _f(d1, "tension", case), _f(d2, "tension", case)
        if t1.shape == t2.shape and np.abs(t1 - t2[::-1]).max() > tol * 10:
            out.append(
                (
                    "swap_tension",
                    f"case {case}: tension differs by {np.abs(t1 - t2[::-1]).max():.3g} N",
                )
            )
    return out
