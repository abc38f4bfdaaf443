"""Figures of the statics seed (dodaran-park)."""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr

from . import register

#: dodaran-park seed, Table 1: points of the steel catenary of Fig. 4 (x, z) [m]
TABLE1 = np.array([
    [0.0, 0.0], [5.25, -2.5], [25.67, -12.5], [58.64, -17.5], [65.85, -15.5],
    [79.64, -12.65], [82.91, -9.56], [92.5, -8.6],
])


@register("dodaran-fig4", ("catenary-in-air",))
def fig4(data: dict[str, xr.Dataset], out: Path) -> Path:
    ds = data["catenary-in-air"]
    fig, ax = plt.subplots(figsize=(6, 3.5))
    ax.plot(ds["x"], ds["z"], "-", label="cablestudy (exact elastic catenary)")
    ax.plot(TABLE1[:, 0], TABLE1[:, 1], "o", mfc="none", label="seed Table 1")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("z [m]")
    ax.set_title("Elastic steel catenary in air, L = 100 m (dodaran-park Fig. 4)")
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    path = out / "dodaran-fig4.png"
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path
