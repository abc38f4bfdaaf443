"""Figures of the vaz-patel seed's static examples (shooting solver): a segmented
deep-water mooring line in a sheared current, and a telecommunication cable in a
current that turns with depth."""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr

from .registry import register, save


def _labels(ds: xr.Dataset, dim: str, unit: str) -> list[str]:
    """Legend labels of a sweep dimension: the values of the swept path where the axis
    is a zip (coordinate ``<dim>_<path end>``), else the dimension's own values."""
    extra = [c for c in ds.coords if c != dim and c.startswith(f"{dim}_") and ds[c].dims == (dim,)]
    values = ds[extra[0]].values if extra else ds[dim].values
    return [f"{v:g} {unit}" for v in values]


def _segment_ends(ds: xr.Dataset) -> list[float]:
    """Interior segment boundaries [m] from the study YAML kept in the dataset."""
    import yaml

    study = yaml.safe_load(ds.attrs["study_yaml"])
    lengths = [float(seg["length"]) for seg in study["line"]["segments"]]
    return list(np.cumsum(lengths)[:-1])


def _solved(ds: xr.Dataset, dim: str, labels: list[str]) -> list[tuple[str, xr.Dataset]]:
    """(label, case) of each case along ``dim`` that solved (status 0)."""
    cases = [(label, ds.isel({dim: i})) for i, label in enumerate(labels)]
    return [(label, case) for label, case in cases if int(case["status"]) == 0]


def _grid_legend(axes: Iterable[plt.Axes]) -> None:
    """A light grid and a small legend on each of ``axes``."""
    for ax in axes:
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)


def _profile_panels(axes: list[plt.Axes], ds: xr.Dataset, dim: str, labels: list[str]) -> None:
    """Elevation and azimuth of the tangent [deg] and elongation [m] along s, the
    seed's other outputs (cablestudy.physics.profile)."""
    for label, case in _solved(ds, dim, labels):
        axes[0].plot(case["s"], np.degrees(case["elevation"]), label=label)
        axes[1].plot(case["s"], np.degrees(case["azimuth"]), label=label)
        axes[2].plot(case["s"], case["elongation"], label=label)
    what = ("elevation of the tangent [deg]", "azimuth of the tangent [deg]", "elongation [m]")
    for ax, ylabel in zip(axes, what, strict=True):
        ax.set(xlabel="unstretched arc length s [m]", ylabel=ylabel)
    _grid_legend(axes)


def _tensions(ax: plt.Axes, case: xr.Dataset, label: str) -> None:
    """Effective tension (solid) and actual wall tension (dashed, same colour) [kN]."""
    (line,) = ax.plot(case["s"], case["tension"] / 1e3, label=label)
    ax.plot(case["s"], case["tension_wall"] / 1e3, "--", color=line.get_color(), lw=0.9)


@register("vaz-patel-mooring", ("vaz-patel-segmented-mooring",))
def mooring(data: dict[str, xr.Dataset], out: Path) -> Path:
    ds = data["vaz-patel-segmented-mooring"]
    dim = "current_heading"
    labels = _labels(ds, dim, "deg")
    fig, grid = plt.subplots(2, 3, figsize=(13, 8))
    axes = grid[0]
    for label, case in _solved(ds, dim, labels):
        laid = float(case["laid_length"])
        axes[0].plot(case["x"], case["z"], label=f"current {label}, laid {laid:.0f} m")
        axes[1].plot(case["x"], case["y"], label=f"current {label}")
        fb = -case["force_b"].values
        _tensions(
            axes[2],
            case,
            f"{label}: top H = {np.hypot(fb[0], fb[1]) / 1e3:.1f} kN, V = {fb[2] / 1e3:.1f} kN",
        )
    for s_b in _segment_ends(ds):
        axes[2].axvline(s_b, color="0.6", lw=0.8, ls="--")
    axes[0].set(xlabel="x [m]", ylabel="z [m]", title="elevation")
    axes[1].set(xlabel="x [m]", ylabel="y [m]", title="plan")
    axes[2].set(
        xlabel="unstretched arc length from anchor s [m]",
        ylabel="tension [kN]",
        title="effective (solid), wall (dashed) tension; grey: joints",
    )
    _grid_legend(axes)
    _profile_panels(list(grid[1]), ds, dim, [f"current {lab}" for lab in labels])
    fig.suptitle(
        "Segmented deep-water mooring in a sheared current (vaz-patel example 2, shooting solver)",
        fontsize=10,
    )
    return save(fig, out / "vaz-patel-mooring.png")


@register("vaz-patel-turning-current", ("vaz-patel-turning-current",))
def turning_current(data: dict[str, xr.Dataset], out: Path) -> Path:
    ds = data["vaz-patel-turning-current"]
    dim = "lower_heading"
    labels = _labels(ds, dim, "deg")
    fig = plt.figure(figsize=(11, 11))
    spec = fig.add_gridspec(3, 6)
    axes = np.array(
        [[fig.add_subplot(spec[r, 0:3]), fig.add_subplot(spec[r, 3:6])] for r in range(2)]
    )
    (ax_xz, ax_xy), (ax_yz, ax_t) = axes
    row3 = [fig.add_subplot(spec[2, 2 * k : 2 * k + 2]) for k in range(3)]
    for label, case in _solved(ds, dim, labels):
        text = f"lower current {label}"
        ax_xz.plot(case["x"], case["z"], label=text)
        ax_xy.plot(case["x"], case["y"], label=f"{text}, laid {float(case['laid_length']):.0f} m")
        ax_yz.plot(case["y"], case["z"], label=text)
        _tensions(ax_t, case, text)
    ax_xz.set(xlabel="x [m]", ylabel="z [m]", title="elevation (x-z)")
    ax_xy.set(xlabel="x [m]", ylabel="y [m]", title="plan (x-y)")
    ax_yz.set(xlabel="y [m]", ylabel="z [m]", title="side (y-z)")
    ax_t.set(
        xlabel="unstretched arc length from the seabed end s [m]",
        ylabel="tension [kN]",
        title="effective (solid) and wall (dashed) tension",
    )
    _grid_legend(axes.flat)
    _profile_panels(row3, ds, dim, [f"lower current {lab}" for lab in labels])
    fig.suptitle(
        "HA telecommunication cable (seed Table 1) in a current turning with depth "
        "(vaz-patel example 3, shooting solver)",
        fontsize=10,
    )
    return save(fig, out / "vaz-patel-turning-current.png")


@register("vaz-patel-cable-installation", ("vaz-patel-cable-installation",))
def cable_installation(data: dict[str, xr.Dataset], out: Path) -> Path:
    ds = data["vaz-patel-cable-installation"]
    dim = "speed"
    labels = _labels(ds, dim, "m/s")
    fig, grid = plt.subplots(2, 3, figsize=(13, 8))
    axes = grid[0]
    for label, case in _solved(ds, dim, labels):
        text = f"transverse current {label}"
        axes[0].plot(case["x"], case["z"], label=text)
        axes[1].plot(case["x"], case["y"], label=f"{text}, laid {float(case['laid_length']):.0f} m")
        _tensions(axes[2], case, text)
    axes[0].set(xlabel="x (ship's heading) [m]", ylabel="z [m]", title="elevation")
    axes[1].set(xlabel="x [m]", ylabel="y [m]", title="plan (ship at the right end)")
    axes[2].set(
        xlabel="unstretched arc length from the seabed end s [m]",
        ylabel="tension [kN]",
        title="effective (solid) and wall (dashed) tension",
    )
    _grid_legend(axes)
    _profile_panels(list(grid[1]), ds, dim, [f"current {lab}" for lab in labels])
    fig.suptitle(
        "Steady laying of the HA cable (seed Table 1), ship 1.0 m/s, pay-out "
        "1.05 m/s, in a transverse sheared current (vaz-patel example 1)",
        fontsize=10,
    )
    return save(fig, out / "vaz-patel-cable-installation.png")
