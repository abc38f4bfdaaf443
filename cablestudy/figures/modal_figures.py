"""Figures of the modal analysis: natural frequencies of a shallow cable against
Irvine's cable parameter lambda^2 (Irvine, *Cable Structures*, 1981, Fig. 3.5 style)."""

from __future__ import annotations

import math
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr
import yaml

from ..dynamics import irvine
from .registry import register, save

#: marker and label of each mode family
FAMILIES = {
    "out_of_plane": ("o", "out of plane"),
    "antisymmetric": ("s", "in plane, antisymmetric"),
    "symmetric": ("^", "in plane, symmetric"),
    "longitudinal": ("x", "longitudinal (bar)"),
}


def classify(shape: np.ndarray) -> str:
    """Family of a mode shape (n_s, 3) of a level cable in the x-z plane."""
    energy = np.nansum(shape**2)
    if np.nansum(shape[:, 1] ** 2) > 0.5 * energy:
        return "out_of_plane"
    if np.nansum(shape[:, 0] ** 2) > 0.5 * energy:
        return "longitudinal"
    z = shape[:, 2]
    return (
        "symmetric"
        if np.nansum((z + z[::-1]) ** 2) > np.nansum((z - z[::-1]) ** 2)
        else "antisymmetric"
    )


@register("irvine-modal-lambda", ("irvine-modal-lambda",))
def irvine_lambda(data: dict[str, xr.Dataset], out: Path) -> Path:
    ds = data["irvine-modal-lambda"]
    study = yaml.safe_load(ds.attrs["study_yaml"])
    seg = study["line"]["segments"][0]
    mass = float(seg["mass_per_length"])
    gravity = float(study["environment"].get("gravity", 9.80665))
    span = float(
        np.hypot(
            *np.subtract(study["ends"]["b"]["position"][:2], study["ends"]["a"]["position"][:2])
        )
    )
    fig, ax = plt.subplots(figsize=(7, 4.5))
    seen: set[str] = set()
    for i in range(ds.sizes["lambda_squared"]):
        case = ds.isel(lambda_squared=i)
        if int(case["status"]) != 0:
            continue
        EA = float(case["lambda_squared_axial_stiffness"])
        L0 = float(case["lambda_squared_length"])
        H = float(np.hypot(case["force_a"].sel(component="x"), case["force_a"].sel(component="y")))
        T = case["tension"].values
        s = case["arc_length"].values if "arc_length" in case else np.linspace(0, L0, T.size)
        effective_length = float(np.trapezoid((T / H) ** 2 * (1 + T / EA), s))
        lam2 = irvine.cable_parameter(
            span=span,
            weight=mass * gravity,
            horizontal_tension=H,
            axial_stiffness=EA,
            effective_length=effective_length,
        )
        arc = float(
            np.sum(
                np.sqrt(np.diff(case["x"]) ** 2 + np.diff(case["y"]) ** 2 + np.diff(case["z"]) ** 2)
            )
        )
        # omega_bar / pi = f / f1 with f1 = sqrt(H / m) / (2 l), m per hanging length
        f1 = math.sqrt(H / (mass * L0 / arc)) / (2 * span)
        for f, shape in zip(
            case["natural_frequency"].values, case["mode_shape"].values, strict=True
        ):
            fam = classify(shape)
            marker, label = FAMILIES[fam]
            ax.plot(
                lam2,
                f / f1,
                marker,
                color=f"C{list(FAMILIES).index(fam)}",
                mfc="none",
                ms=5,
                label=None if fam in seen else f"cablestudy: {label}",
            )
            seen.add(fam)
    lam = np.logspace(0, 3, 300)
    sym = np.array([irvine.symmetric_roots(x, 3) for x in lam]) / math.pi
    for k in range(3):
        ax.plot(
            lam,
            sym[:, k],
            "-",
            color="C2",
            lw=1,
            label="Irvine: symmetric, tan(w/2) = w/2 - (4/lambda^2)(w/2)^3" if k == 0 else None,
        )
    for n in range(1, 5):
        ax.axhline(
            n, color="C0", lw=0.8, ls=":", label="Irvine: out of plane, n" if n == 1 else None
        )
    for n in (1, 2):
        ax.axhline(
            2 * n,
            color="C1",
            lw=0.8,
            ls="--",
            label="Irvine: antisymmetric, 2n" if n == 1 else None,
        )
    ax.axvline(4 * math.pi**2, color="0.5", lw=0.8)
    ax.text(4 * math.pi**2 * 1.05, 0.6, "lambda^2 = 4 pi^2", color="0.4", fontsize=8)
    ax.set_xscale("log")
    ax.set_ylim(0.5, 5.5)
    ax.set_xlabel("Irvine's cable parameter lambda^2 [-]")
    ax.set_ylabel("f / f1,  f1 = sqrt(H/m) / (2 l)  [-]")
    ax.set_title("Shallow level cable, sag/span 1/40: natural frequencies vs lambda^2")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7, loc="upper left", ncol=2)
    return save(fig, out / "irvine-modal-lambda.png")


@register("umbilical-frequency-tension", ("umbilical-frequency-tension",))
def umbilical_frequency_tension(data: dict[str, xr.Dataset], out: Path) -> Path:
    """ajayi Figs. 9-10: lateral natural frequencies of the vertical umbilical (1500
    kg/m) against its bottom tension, with and without EI, and the exact string (EI = 0)
    with linear tension."""
    return _frequency_tension(data["umbilical-frequency-tension"], out, "Figs. 9-10")


@register("umbilical-frequency-tension-30kg", ("umbilical-frequency-tension-30kg",))
def umbilical_frequency_tension_30kg(data: dict[str, xr.Dataset], out: Path) -> Path:
    """ajayi Fig. 11: as Figs. 9-10 for the umbilical tuned to 30 kg/m."""
    return _frequency_tension(data["umbilical-frequency-tension-30kg"], out, "Fig. 11")


@register("umbilical-frequency-tension-60kg", ("umbilical-frequency-tension-60kg",))
def umbilical_frequency_tension_60kg(data: dict[str, xr.Dataset], out: Path) -> Path:
    """ajayi Fig. 12: as Figs. 9-10 for the umbilical tuned to 60 kg/m."""
    return _frequency_tension(data["umbilical-frequency-tension-60kg"], out, "Fig. 12")


def _frequency_tension(ds: xr.Dataset, out: Path, figures: str) -> Path:
    from scipy.optimize import brentq

    from ..dynamics.strings import linear_tension_string

    study = yaml.safe_load(ds.attrs["study_yaml"])
    seg = study["line"]["segments"][0]
    env = study["environment"]
    rho = 1025.0 if env.get("fluid", "water") == "water" else float(env["fluid"]["density"])
    gravity = float(env.get("gravity", 9.80665))
    area = math.pi * float(seg["diameter"]) ** 2 / 4
    m = float(seg["mass_per_length"])
    # the weight in water where the study gives it (it then overrides mass - buoyancy)
    w = float(seg.get("weight_in_fluid", (m - rho * area) * gravity))
    m_total = m + rho * float(seg.get("added_mass_normal", 1.0)) * area
    EA = float(seg["axial_stiffness"])
    height = abs(study["ends"]["b"]["position"][2] - study["ends"]["a"]["position"][2])

    fig, ax = plt.subplots(figsize=(7, 4.5))
    n_lateral = ds.sizes["mode"] // 2
    T0 = np.geomspace(float(ds["tension_a"].min()) * 0.8, float(ds["tension_a"].max()) * 1.25, 40)
    curves = []
    for t0 in T0:
        L0 = brentq(
            lambda L, t0=t0: L + (t0 * L + w * L * L / 2) / EA - height,
            0.9 * height,
            height,
            xtol=1e-12,
        )
        curves.append(
            linear_tension_string(
                length=L0, bottom_tension=t0, weight=w, mass=m_total, count=n_lateral
            )
        )
    curves_arr = np.array(curves)
    for k in range(n_lateral):
        ax.plot(
            T0,
            curves_arr[:, k],
            "-",
            color=f"C{k}",
            lw=1,
            label="string, T = T0 + w s (Bessel roots)" if k == 0 else None,
        )
    for j, EI in enumerate(ds["bending_stiffness"].values):
        sub = ds.isel(bending_stiffness=j)
        ok = sub["status"].values == 0
        tension = sub["tension_a"].values[ok]
        freq = sub["natural_frequency"].values[ok][:, 0::2]  # lateral modes come in pairs
        for k in range(n_lateral):
            ax.plot(
                tension,
                freq[:, k],
                "o" if EI == 0 else "s",
                color=f"C{k}",
                mfc="none" if EI == 0 else f"C{k}",
                ms=5,
                label=(f"cablestudy, EI = {EI:.3g} N m^2" if k == 0 else None),
            )
    ax.set_xscale("log")
    ax.set_xlabel("bottom tension T0 [N]")
    ax.set_ylabel("natural frequency [Hz]")
    ax.set_title(
        f"ajayi {figures}: vertical umbilical of {m:g} kg/m in 1200 m of water (Table 1 "
        f"section): lateral modes 1-{n_lateral}",
        fontsize=9,
    )
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    return save(fig, out / f"{ds.attrs['study_name']}.png")
