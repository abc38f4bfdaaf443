"""The registry of paper figures: each builder module registers its figures here
(:func:`register`), and :func:`cablestudy.figures.build_all` builds what is registered."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import xarray as xr

Builder = Callable[[dict[str, xr.Dataset], Path], Path]

#: figure name -> (study names read, builder writing the PNG and returning its path)
FIGURES: dict[str, tuple[tuple[str, ...], Builder]] = {}


def register(name: str, studies: tuple[str, ...]) -> Callable[[Builder], Builder]:
    def deco(fn: Builder) -> Builder:
        FIGURES[name] = (studies, fn)
        return fn

    return deco


def save(fig: Any, path: Path) -> Path:
    """Lay out the matplotlib figure ``fig``, write it to ``path`` (PNG, 120 dpi) and close
    it; returns ``path``."""
    import matplotlib.pyplot as plt

    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path
