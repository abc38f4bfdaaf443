"""Figures 4-8 of the umbilical seed (ajayi): normal, tangential and transverse
displacement and velocity of the line over its length and time, as space-time plots.

The seed resolves the motion on the static line's local axes: ``p`` along the static
tangent t (s from the bottom end upwards), ``q`` along the normal n in the plane of the
line, ``z`` along the transverse (binormal, horizontal) b. :func:`line_frames` builds
these axes from the static shape stored in the same dataset, :func:`local_motion`
resolves the point histories (``history_displacement``, ``history_velocity``) on them.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr
import yaml
from scipy.optimize import curve_fit

from .registry import Builder, register, save

STUDY = "umbilical-time-response"


def line_frames(
    position: np.ndarray, s: np.ndarray, *, reference: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Local axes (t, n, b) of a static line, each (n_points, 3) of unit vectors.

    t is the tangent d(position)/ds (towards increasing s). The plane of the line is the
    vertical plane through the horizontal direction h along which the line's points lie
    away from end A (the dominant singular vector of their horizontal offsets); a line
    whose points all lie on the vertical through A has no plane of its own and takes h
    from ``reference`` (its horizontal part). b is the horizontal normal of that plane,
    z x h, made normal to t; n = b x t lies in the plane, normal to t.

    Parameters
    ----------
    position : [m] (n_points, 3) static positions, z up
    s : [m] (n_points,) arc length of the points (increasing)
    reference : [-] (3,) direction whose horizontal part sets the plane of a vertical line
    """
    position = np.asarray(position, dtype=float)
    t = np.gradient(position, np.asarray(s, dtype=float), axis=0)
    t /= np.linalg.norm(t, axis=1, keepdims=True)
    offsets = position[:, :2] - position[0, :2]
    span = float(np.ptp(position, axis=0).max())
    _, sing, vt = np.linalg.svd(offsets, full_matrices=False)
    if sing[0] > 1e-9 * max(span, 1.0):
        h = vt[0]
        if float(np.sum(offsets @ h)) < 0.0:
            h = -h
    else:
        if reference is None or np.linalg.norm(np.asarray(reference, float)[:2]) == 0.0:
            raise ValueError(
                "the static line is vertical and has no plane of its own: give a reference "
                "direction with a horizontal part"
            )
        h = np.asarray(reference, dtype=float)[:2]
        h = h / np.linalg.norm(h)
    b0 = np.array([-h[1], h[0], 0.0])  # z x h
    b = b0[None, :] - (t @ b0)[:, None] * t
    b /= np.linalg.norm(b, axis=1, keepdims=True)
    n = np.cross(b, t)
    return t, n, b


def first_case(ds: xr.Dataset) -> xr.Dataset:
    """The first case of a study (index 0 along every sweep dimension)."""
    keep = {"s", "point", "time", "component", "mode"}
    return ds.isel({d: 0 for d in ds.dims if d not in keep})


def _reference_direction(ds: xr.Dataset) -> np.ndarray | None:
    study = yaml.safe_load(ds.attrs.get("study_yaml", "")) or {}
    exc = study.get("analysis", {}).get("dynamic", {}).get("excitation")
    if isinstance(exc, list):
        exc = exc[0] if exc else None
    if not isinstance(exc, dict) or "direction" not in exc:
        return None
    return np.asarray(exc["direction"], dtype=float)


def local_motion(ds: xr.Dataset) -> xr.Dataset:
    """The point histories of one case resolved on the static line's local axes.

    Returns a dataset on (s, time) (s: arc length of the history points [m], time [s])
    with ``{tangential,normal,transverse}_{displacement,velocity}`` [m], [m/s]."""
    ds = first_case(ds)
    s_static = ds["s"].values
    position = np.stack([ds[c].values for c in ("x", "y", "z")], axis=1)
    t, n, b = line_frames(position, s_static, reference=_reference_direction(ds))
    sp = ds["history_point_s"].values
    axes = {}
    for name, frame in (("tangential", t), ("normal", n), ("transverse", b)):
        f = np.stack([np.interp(sp, s_static, frame[:, k]) for k in range(3)], axis=1)
        axes[name] = f / np.linalg.norm(f, axis=1, keepdims=True)
    out = xr.Dataset(coords={"s": ("s", sp, {"units": "m"})})
    out = out.assign_coords(time=("time", ds["history_time"].values, {"units": "s"}))
    for quantity, units in (("displacement", "m"), ("velocity", "m/s")):
        hist = ds[f"history_{quantity}"].transpose("point", "time", "component").values
        for name, f in axes.items():
            out[f"{name}_{quantity}"] = (
                ("s", "time"),
                np.einsum("ptc,pc->pt", hist, f),
                {"units": units, "long_name": f"{name} {quantity}"},
            )
    return out


def oscillation_period(time: np.ndarray, signal: np.ndarray) -> tuple[float, float, float]:
    """Period [s], decay rate [1/s] and relative misfit [-] of a damped oscillation about
    a constant, ``c + exp(-a t) (A cos wt + B sin wt)``, fitted by least squares; the
    starting frequency is the peak of the (zero-padded) spectrum of the signal minus its
    mean. The misfit is the rms residual over the rms of the signal about its mean (it
    measures what one mode leaves out, e.g. higher modes in the record)."""
    time = np.asarray(time, dtype=float)
    y = np.asarray(signal, dtype=float)
    t0 = time - time[0]
    yd = y - y.mean()
    pad = 8 * len(t0)
    freq = np.fft.rfftfreq(pad, float(t0[1] - t0[0]))
    power = np.abs(np.fft.rfft(yd, pad))
    f0 = freq[1 + int(np.argmax(power[1:]))]

    def model(tt: np.ndarray, c: float, a: float, ca: float, cb: float, w: float) -> np.ndarray:
        return c + np.exp(-a * tt) * (ca * np.cos(w * tt) + cb * np.sin(w * tt))

    p, _ = curve_fit(model, t0, y, p0=[y.mean(), 0.0, yd[0], 0.0, 2 * np.pi * f0], maxfev=20000)
    misfit = float(np.std(y - model(t0, *p)) / np.std(yd))
    return float(2 * np.pi / abs(p[4])), float(p[1]), misfit


def ramp_end(ds: xr.Dataset) -> float:
    """Time [s] at which the study's end motion reaches its last value (the end of the
    ramp-and-hold table), 0 for a harmonic excitation."""
    study = yaml.safe_load(ds.attrs["study_yaml"])
    exc = study["analysis"]["dynamic"]["excitation"]
    table = exc.get("table") if isinstance(exc, dict) else None
    if not table:
        return 0.0
    last = table[-1][1]
    return float(next(t for t, d in table if d == last))


def free_period(ds: xr.Dataset, component: str, s: float) -> tuple[float, float, float]:
    """:func:`oscillation_period` of one local component's displacement at the history
    point nearest arc length ``s`` [m], after the ramp (and one more 20 s for the start
    transient of the held offset)."""
    motion = local_motion(ds)
    q = motion[f"{component}_displacement"].sel(s=s, method="nearest")
    t = motion["time"].values
    keep = t >= ramp_end(ds) + 20.0
    return oscillation_period(t[keep], q.values[keep])


def _excitation_text(ds: xr.Dataset) -> str:
    """The end motion of the study in words, for the figure titles."""
    exc = yaml.safe_load(ds.attrs["study_yaml"])["analysis"]["dynamic"]["excitation"]
    if isinstance(exc, list):
        return "under several end motions"
    direction = np.asarray(exc["direction"], dtype=float)
    angle = np.degrees(np.arctan2(direction[1], direction[0]))
    where = f"{angle:.0f} deg from x (the plane of the current)"
    if "table" in exc:
        return f"under a {exc['table'][-1][1]:g} m offset of end {exc['end']}, {where}"
    if "amplitude" in exc:
        return (
            f"under a {exc['amplitude']:g} m, {1.0 / exc['frequency']:g} s motion of end "
            f"{exc['end']}, {where}"
        )
    return f"under end motion of end {exc['end']}"


#: (seed figure, variable, colour-bar label)
SEED_FIGURES = (
    (4, "normal_displacement", "normal displacement q [m]"),
    (5, "normal_velocity", "normal velocity dq/dt [m/s]"),
    (6, "tangential_displacement", "tangential displacement p [m]"),
    (7, "tangential_velocity", "tangential velocity dp/dt [m/s]"),
    (8, "transverse_displacement", "transverse displacement z [m]"),
)


def _space_time(motion: xr.Dataset, variable: str, label: str, title: str, path: Path) -> Path:
    field = motion[variable]
    limit = float(np.abs(field).max()) or 1.0
    fig, ax = plt.subplots(figsize=(7.5, 4.5))
    mesh = ax.pcolormesh(
        motion["time"].values,
        motion["s"].values,
        field.values,
        cmap="RdBu_r",
        vmin=-limit,
        vmax=limit,
        shading="nearest",
    )
    fig.colorbar(mesh, ax=ax, label=label)
    ax.set_xlabel("time t [s]")
    ax.set_ylabel("arc length s from the bottom end [m]")
    ax.set_title(title, fontsize=9)
    return save(fig, path)


def _builder(number: int, variable: str, label: str) -> Builder:
    """Register the space-time builder of one seed figure."""
    name = f"umbilical-fig{number}-{variable.replace('_', '-')}"

    def build(data: dict[str, xr.Dataset], out: Path) -> Path:
        ds = data[STUDY]
        motion = local_motion(ds)
        title = (
            f"ajayi Fig. {number}: {label.split(' [')[0]} of the umbilical (EI, c) standing "
            f"in 1200 m of water,\nfrom rest, {_excitation_text(ds)}"
        )
        return _space_time(motion, variable, label, title, out / f"{name}.png")

    build.__name__ = f"umbilical_fig{number}"
    build.__doc__ = f"ajayi Fig. {number}: {label} over arc length and time (space-time plot)."
    return register(name, (STUDY,))(build)


for _number, _variable, _label in SEED_FIGURES:
    _builder(_number, _variable, _label)
