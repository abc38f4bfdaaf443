"""Figures of the dynamics seed (moustafa): tension against excitation frequency, and
midpoint histories. Cases whose steady state did not settle (steady_converged = 0)
are drawn with open markers, so a number that is not final never looks final."""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr

from .registry import register, save


def _curves(ax: plt.Axes, ds: xr.Dataset, dim: str, value: float, label: str, color: str) -> None:
    sel = ds.sel({dim: value}) if dim else ds
    f = sel["frequency"].values
    ok = sel["status"].values == 0
    conv = ok & (sel["steady_converged"].values == 1)
    for var, style in (("tension_max", "-"), ("tension_min", "--")):
        y = np.where(ok, sel[var].values, np.nan)
        ax.plot(f, y, style, color=color, label=f"{label} {var.split('_')[1]}")
        ax.plot(f[conv], y[conv], "o", color=color, ms=3)
        ax.plot(f[ok & ~conv], y[ok & ~conv], "o", mfc="none", color=color, ms=5)
    ax.axhline(float(np.nanmean(sel["tension_static"].values)), color=color, lw=0.6, ls=":")


def _finish(fig: plt.Figure, ax: plt.Axes, title: str, path: Path) -> Path:
    _finish_axes(ax, title)
    return save(fig, path)


@register("moustafa-figs2-5", ("moustafa-figs2-5", "moustafa-figs2-5-methods"))
def figs2_5(data: dict[str, xr.Dataset], out: Path) -> Path:
    """Per amplitude: time-domain max/min (black, filled markers where steady, open
    where not settled), frequency-domain max/min (blue lines), and the answer of
    ``method: auto`` (the moustafa-figs2-5 study) as green dots where it kept the
    frequency domain and red rings where it ran the time domain."""
    auto = data["moustafa-figs2-5"]
    both = data["moustafa-figs2-5-methods"]
    methods = [str(m) for m in both["method"].values]

    def method(name: str) -> xr.Dataset:
        return both.isel(method=methods.index(name))

    fig, axes = plt.subplots(2, 2, figsize=(10, 7.5), sharex=True)
    for ax, amp, n in zip(axes.flat, auto["amplitude"].values, (2, 3, 4, 5), strict=False):
        _curves(ax, method("time"), "amplitude", float(amp), "time", "k")
        fd = method("frequency").sel(amplitude=amp)
        ok = fd["status"].values == 0
        f = fd["frequency"].values
        for var, style in (("tension_max", "-"), ("tension_min", "--")):
            ax.plot(
                f,
                np.where(ok, fd[var].values, np.nan),
                style,
                color="C0",
                lw=1.2,
                label=f"frequency {var.split('_')[1]}",
            )
        sel = auto.sel(amplitude=amp)
        chose = sel["dynamic_method"].values == "frequency"
        good = sel["status"].values == 0
        for var in ("tension_max", "tension_min"):
            y = np.where(good, sel[var].values, np.nan)
            ax.plot(
                f[chose],
                y[chose],
                "o",
                color="C2",
                ms=6,
                mfc="none",
                mew=1.5,
                label="auto: frequency" if var == "tension_max" else None,
            )
            ax.plot(
                f[~chose],
                y[~chose],
                "s",
                color="C3",
                ms=6,
                mfc="none",
                mew=1.0,
                label="auto: time" if var == "tension_max" else None,
            )
        ax.set_xlabel("excitation frequency [Hz]")
        ax.set_ylabel("tension [N]")
        ax.set_title(f"Moustafa Fig. {n}: amplitude {amp:g} m (dotted: static)", fontsize=9)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=6, ncol=2)
    fig.suptitle(
        "Max/min tension at the excited end: time domain (black; open: not settled), "
        "frequency domain (blue), method auto's choice (markers)",
        fontsize=9,
    )
    return save(fig, out / "moustafa-figs2-5.png")


@register("moustafa-fig6", ("moustafa-fig6",))
def fig6(data: dict[str, xr.Dataset], out: Path) -> Path:
    ds = data["moustafa-fig6"]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for i, span in enumerate(ds["span"].values):
        t0 = float(ds["tension_static"].sel(span=span).mean())
        _curves(ax, ds, "span", float(span), f"span {span:g} m, T0 = {t0:.0f} N", f"C{i}")
    return _finish(
        fig,
        ax,
        "Moustafa Fig. 6: effect of the initial tension (amplitude 0.075 m)",
        out / "moustafa-fig6.png",
    )


@register("moustafa-fig7", ("moustafa-fig7",))
def fig7(data: dict[str, xr.Dataset], out: Path) -> Path:
    ds = data["moustafa-fig7"]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    area = np.pi * 0.01**2 / 4.0
    for i, ea in enumerate(ds["axial_stiffness"].values):
        _curves(ax, ds, "axial_stiffness", float(ea), f"E = {ea / area:.2g} Pa", f"C{i}")
    return _finish(
        fig,
        ax,
        "Moustafa Fig. 7: effect of Young's modulus (amplitude 0.075 m)",
        out / "moustafa-fig7.png",
    )


@register("moustafa-sensitivity", ("moustafa-sensitivity",))
def sensitivity(data: dict[str, xr.Dataset], out: Path) -> Path:
    """Water (the seed's case) and air in separate panels, each on its own scale: in air
    the only damping is the air drag, so near resonance the tension spikes (and may not
    settle) far above the water curves. The air panel's axis stops at 1.3 times the
    largest settled value; values beyond it are marked by triangles on the top edge,
    with the largest one written there."""
    ds = data["moustafa-sensitivity"]
    fluids = [str(f) for f in ds["fluid"].values]
    fig, axes = plt.subplots(1, len(fluids), figsize=(6 * len(fluids), 4.5), squeeze=False)
    for ax, fluid in zip(axes[0], fluids, strict=True):
        sub = ds.sel(fluid=fluid)
        for i, ea in enumerate(sub["axial_stiffness"].values):
            _curves(ax, sub, "axial_stiffness", float(ea), f"EA = {ea:.3g} N", f"C{i}")
        ok = (sub["status"].values == 0) & (sub["steady_converged"].values == 1)
        settled = np.where(ok, sub["tension_max"].values, np.nan)
        top = 1.3 * float(np.nanmax(settled)) if np.isfinite(settled).any() else None
        _finish_axes(ax, f"{fluid} (amplitude 0.075 m)")
        if top is not None:
            ax.set_ylim(0.0, top)
            over = np.where(sub["status"].values == 0, sub["tension_max"].values, np.nan) > top
            if over.any():
                f = np.broadcast_to(sub["frequency"].values, over.shape)[over]
                ax.plot(f, np.full(f.size, top), "^", color="k", ms=6, clip_on=False)
                big = float(np.nanmax(sub["tension_max"].values))
                ax.text(
                    0.02,
                    0.97,
                    f"triangles: off scale (up to {big:.3g} N)",
                    transform=ax.transAxes,
                    fontsize=7,
                    va="top",
                )
    fig.suptitle("Sensitivity to the seed's readings: fluid and EA", fontsize=10)
    return save(fig, out / "moustafa-sensitivity.png")


def _finish_axes(ax: plt.Axes, title: str) -> None:
    ax.set_xlabel("excitation frequency [Hz]")
    ax.set_ylabel("tension at the excited end [N]")
    ax.set_title(title, fontsize=9)
    ax.set_ylim(bottom=0.0)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, ncol=2)


@register("moustafa-figs8-10", ("moustafa-figs8-10",))
def figs8_10(data: dict[str, xr.Dataset], out: Path) -> Path:
    ds = data["moustafa-figs8-10"]
    n = ds.sizes["excitation_case"]
    fig, axes = plt.subplots(3, n, figsize=(4 * n, 7), sharex="col")
    amps = ds["excitation_case_amplitude"].values
    freqs = ds["excitation_case_frequency"].values
    quantities = (
        ("history_displacement", "displacement [m]"),
        ("history_velocity", "velocity [m/s]"),
        ("history_acceleration", "acceleration [m/s^2]"),
    )
    for j in range(n):
        case = ds.isel(excitation_case=j)
        t = case["history_time"].values
        t = t - t[0]
        for i, (var, label) in enumerate(quantities):
            ax = axes[i, j]
            ax.plot(t, case[var].isel(point=0).sel(component="z").values, lw=1)
            ax.set_ylabel(label)
            ax.grid(alpha=0.3)
        axes[0, j].set_title(f"Fig. {8 + j}: midpoint, {amps[j]:g} m, {freqs[j]:g} Hz", fontsize=9)
        axes[-1, j].set_xlabel("time in the steady window [s]")
    fig.suptitle("Moustafa Figs. 8-10: vertical response of the cable midpoint (z up)", fontsize=10)
    return save(fig, out / "moustafa-figs8-10.png")
