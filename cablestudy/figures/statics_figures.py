"""Figures of the statics seed (dodaran-park)."""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr

from .registry import register, save

#: dodaran-park seed, Table 1: points of the steel catenary of Fig. 4 (x, z) [m]
TABLE1 = np.array(
    [
        [0.0, 0.0],
        [5.25, -2.5],
        [25.67, -12.5],
        [58.64, -17.5],
        [65.85, -15.5],
        [79.64, -12.65],
        [82.91, -9.56],
        [92.5, -8.6],
    ]
)


def table1_chord_excess() -> np.ndarray:
    """Height [m] of each interior Table 1 point above the chord of its neighbours.

    A line hanging under its own weight is convex (z'' = w / H sqrt(1 + z'^2) > 0), so
    every point of it lies on or below the chord of its neighbours: a positive value
    is a point no hanging line passes through."""
    x, z = TABLE1[:, 0], TABLE1[:, 1]
    chord = z[:-2] + (z[2:] - z[:-2]) * (x[1:-1] - x[:-2]) / (x[2:] - x[:-2])
    return z[1:-1] - chord


@register("dodaran-fig4", ("catenary-in-air", "dodaran-fig4-semi-analytic"))
def fig4(data: dict[str, xr.Dataset], out: Path) -> Path:
    ds = data["catenary-in-air"]
    semi = data["dodaran-fig4-semi-analytic"]
    fig, ax = plt.subplots(figsize=(6, 3.5))
    ax.plot(semi["x"], semi["z"], "-", label="cablestudy semi-analytic (method catenary)")
    ax.plot(
        ds["x"][::10],
        ds["z"][::10],
        "s",
        mfc="none",
        ms=5,
        label="exact elastic catenary (Irvine 1981)",
    )
    ax.plot(TABLE1[:, 0], TABLE1[:, 1], "o", mfc="none", label="seed Table 1")
    miss = TABLE1[:, 1] - np.interp(TABLE1[:, 0], ds["x"].values, ds["z"].values)
    excess = table1_chord_excess()
    ax.text(
        0.02,
        0.03,
        f"Table 1 lies {np.sqrt(np.mean(miss**2)):.2f} m rms from the exact curve: its points "
        f"at x = {TABLE1[6, 0]:g} m and {TABLE1[4, 0]:g} m\nlie {excess[5]:.2f} m and "
        f"{excess[3]:.2f} m above the chord of their neighbours, which no hanging line can "
        "do\n(see docs/validation.md)",
        transform=ax.transAxes,
        fontsize=6.5,
    )
    ax.set_xlabel("x [m]")
    ax.set_ylabel("z [m]")
    ax.set_title("Elastic steel catenary in air, L = 100 m (dodaran-park Fig. 4)")
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    return save(fig, out / "dodaran-fig4.png")


@register("dodaran-fig5", ("dodaran-fig5-point-load",))
def fig5(data: dict[str, xr.Dataset], out: Path) -> Path:
    ds = data["dodaran-fig5-point-load"]
    fig, ax = plt.subplots(figsize=(6, 3.5))
    for i, load in enumerate(ds["point_load"].values):
        case = ds.isel(point_load=i)
        ax.plot(case["x"], case["z"], "-", label=f"point load {abs(load) / 1e3:.2g} kN at s = 50 m")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("z [m]")
    ax.set_title("Cable under a point load, L = 100 m (dodaran-park Fig. 5)", fontsize=10)
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    return save(fig, out / "dodaran-fig5.png")


def _current_figure(ds: xr.Dataset, title: str, out: Path, name: str) -> Path:
    styles = {0: ("--", "no current"), 1: ("-.", "U = {:.3g} m/s"), 2: ("-", "U = {:.3g} m/s")}
    fig, ax = plt.subplots(figsize=(5, 5))
    for i, speed in enumerate(ds["current_speed"].values):
        case = ds.isel(current_speed=i)
        ls, label = styles.get(i, ("-", "U = {:.3g} m/s"))
        ax.plot(case["x"], case["z"], ls, label=label.format(speed))
    ax.set_xlabel("x [m]")
    ax.set_ylabel("z [m]")
    ax.set_title(title, fontsize=9)
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    return save(fig, out / f"{name}.png")


@register("dodaran-fig6", ("dodaran-fig6-marine-cable-340",))
def fig6(data: dict[str, xr.Dataset], out: Path) -> Path:
    return _current_figure(
        data["dodaran-fig6-marine-cable-340"],
        "Marine cable L = 340 m in current (dodaran-park Fig. 6)",
        out,
        "dodaran-fig6",
    )


@register("dodaran-fig7", ("dodaran-fig7-marine-cable-310",))
def fig7(data: dict[str, xr.Dataset], out: Path) -> Path:
    return _current_figure(
        data["dodaran-fig7-marine-cable-310"],
        "Marine cable L = 310 m in current (dodaran-park Fig. 7)",
        out,
        "dodaran-fig7",
    )


@register("dodaran-fig8", ("dodaran-fig8-submersible-3d",))
def fig8(data: dict[str, xr.Dataset], out: Path) -> Path:
    ds = data["dodaran-fig8-submersible-3d"]
    fig = plt.figure(figsize=(9, 4))
    ax3 = fig.add_subplot(1, 2, 1, projection="3d")
    ax2 = fig.add_subplot(1, 2, 2)
    for i, speed in enumerate(ds["current_speed"].values):
        case = ds.isel(current_speed=i)
        ls = "-." if speed == 0.0 else "-"
        label = "no current" if speed == 0.0 else f"U = {speed:.3g} m/s"
        ax3.plot(case["x"], case["y"], case["z"], ls, label=label)
        ax2.plot(case["x"], case["y"], ls, label=label)
    ax3.set_xlabel("x [m]")
    ax3.set_ylabel("y [m]")
    ax3.set_zlabel("z [m]")
    ax3.set_title("3D submersible cable, L = 300 m", fontsize=9)
    ax2.set_xlabel("x [m]")
    ax2.set_ylabel("y [m]")
    ax2.set_title("plan view (dodaran-park Fig. 8)", fontsize=9)
    ax2.grid(alpha=0.3)
    ax2.legend(fontsize=8)
    return save(fig, out / "dodaran-fig8.png")
