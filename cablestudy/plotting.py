"""Quick-look plots of a result file: any variable against any dimension, labelled with
its long name and units (xarray's plotting, matplotlib's Agg backend: no screen).

``quick_look(ds, var, ...)`` returns the matplotlib figure (tests inspect its labels);
``plot_result(path, var, ...)`` opens a result file and writes a PNG.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr


class PlotError(ValueError):
    """A plot that cannot be drawn; the message names the bad name and the valid ones."""


def _label(obj: xr.DataArray, name: str) -> str:
    long_name = obj.attrs.get("long_name", name)
    units = obj.attrs.get("units", "1")
    return f"{long_name} [{units}]"


def _coerce(coord: xr.DataArray, text: str) -> Any:
    if np.issubdtype(coord.dtype, np.number):
        try:
            return float(text)
        except ValueError:
            raise PlotError(
                f"--sel {coord.name}={text}: {coord.name} is numeric; give a number"
            ) from None
    return text


def _select(da: xr.DataArray, ds: xr.Dataset, sel: list[str]) -> tuple[xr.DataArray, list[str]]:
    picked = []
    for item in sel:
        dim, sep, value = item.partition("=")
        if not sep:
            raise PlotError(f"--sel {item!r}: write DIM=VALUE, e.g. --sel frequency=0.5")
        if dim not in da.dims:
            raise PlotError(
                f"--sel {item!r}: {da.name} has no dimension {dim!r}; its dimensions: "
                f"{', '.join(map(str, da.dims)) or 'none'}"
            )
        if dim in ds.coords:
            coord = ds[dim]
            key = _coerce(coord, value)
            if isinstance(key, float):
                da = da.sel({dim: key}, method="nearest")
            else:
                if key not in coord.values.tolist():
                    raise PlotError(
                        f"--sel {item!r}: {dim} has no value {value!r}; values: "
                        f"{', '.join(map(str, coord.values.tolist()[:20]))}"
                    )
                da = da.sel({dim: key})
            picked.append(f"{dim} = {da[dim].values.item()!s}")
        else:
            try:
                index = int(value)
                da = da.isel({dim: index})
            except (ValueError, IndexError):
                raise PlotError(
                    f"--sel {item!r}: {dim} has no coordinate; give an index 0..{da.sizes[dim] - 1}"
                ) from None
            picked.append(f"{dim} = {index}")
    return da, picked


#: more curves than this get a colour bar instead of a legend
MAX_LEGEND = 10


def _colours(fig: Any, ax: Any, da: xr.DataArray, hue: str, ds: xr.Dataset) -> Any:
    """Colour of curve k along a colour bar of the ``hue`` values (their index if not
    numeric); the bar is added to ``fig``."""
    from matplotlib import colormaps
    from matplotlib.cm import ScalarMappable
    from matplotlib.colors import Normalize

    values = da[hue].values if hue in da.coords else np.arange(da.sizes[hue])
    numeric = np.issubdtype(values.dtype, np.number)
    c = values.astype(float) if numeric else np.arange(values.size, dtype=float)
    top = float(c.max()) if c.max() > c.min() else float(c.min()) + 1.0
    norm = Normalize(vmin=float(c.min()), vmax=top)
    cmap = colormaps["viridis"]
    bar = fig.colorbar(ScalarMappable(norm=norm, cmap=cmap), ax=ax)
    bar.set_label(_label(ds[hue], hue) if numeric and hue in ds.variables else f"{hue} (index)")
    return lambda k: cmap(norm(c[k]))


def _many_curves(fig: Any, ax: Any, da: xr.DataArray, x: str, hue: str, ds: xr.Dataset) -> None:
    """One curve per ``hue`` value, coloured along a colour bar."""
    colour = _colours(fig, ax, da, hue, ds)
    for k in range(da.sizes[hue]):
        ax.plot(da[x].values, da.isel({hue: k}).values, color=colour(k), lw=1.0)


def _check_dim(name: str | None, flag: str, da: xr.DataArray) -> None:
    if name is not None and name not in da.dims:
        raise PlotError(
            f"{flag} {name!r}: {da.name} has no dimension {name!r} (after --sel); its "
            f"dimensions: {', '.join(map(str, da.dims)) or 'none'}"
        )


def quick_look(
    ds: xr.Dataset,
    var: str,
    *,
    x: str | None = None,
    hue: str | None = None,
    sel: list[str] | None = None,
    shape: bool = False,
) -> Any:
    """A matplotlib figure of ``ds[var]`` (see :func:`plot_result` for the arguments)."""
    import matplotlib

    if "matplotlib.pyplot" not in __import__("sys").modules:
        matplotlib.use("Agg")
    from matplotlib.figure import Figure

    if var not in ds.data_vars:
        raise PlotError(
            f"no variable {var!r} in the result; variables: {', '.join(sorted(ds.data_vars))}"
        )
    da, picked = _select(ds[var], ds, sel or [])
    da = da.squeeze(drop=False)
    fig = Figure(figsize=(7.0, 4.5), layout="constrained")
    ax = fig.add_subplot()
    if shape:
        if "s" not in da.dims or "x" not in ds.data_vars or "z" not in ds.data_vars:
            raise PlotError(
                f"--shape draws profiles on s from the variables x and z; {var!r} has "
                f"dimensions {', '.join(map(str, da.dims)) or 'none'}"
            )
        xs, _ = _select(ds["x"], ds, sel or [])
        zs, _ = _select(ds["z"], ds, sel or [])
        xs, zs = xs.squeeze(drop=False), zs.squeeze(drop=False)
        others = [d for d in xs.dims if d != "s"]
        _check_dim(hue, "--hue", xs)
        if hue is None and len(others) == 1:
            hue = others[0]
        extra = [d for d in others if d != hue and xs.sizes[d] > 1]
        if extra:
            raise PlotError(
                f"--shape: pick one value of {', '.join(extra)} with --sel DIM=VALUE "
                "(or draw it with --hue)"
            )
        if hue is None:
            ax.plot(xs.values.ravel(), zs.values.ravel())
        else:
            many = xs.sizes[hue] > MAX_LEGEND
            colour = _colours(fig, ax, xs, hue, ds) if many else None
            for k in range(xs.sizes[hue]):
                label = f"{hue} = {xs[hue].values[k]!s}" if hue in xs.coords else f"{hue} {k}"
                ax.plot(
                    xs.isel({hue: k}).values.ravel(),
                    zs.isel({hue: k}).values.ravel(),
                    label=label,
                    color=colour(k) if colour else None,
                )
            if not many:
                ax.legend(fontsize="small")
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_xlabel(_label(ds["x"], "x"))
        ax.set_ylabel(_label(ds["z"], "z"))
        ax.set_title(", ".join(picked) or str(ds.attrs.get("study_name", "")))
        return fig
    _check_dim(x, "--x", da)
    _check_dim(hue, "--hue", da)
    dims = list(da.dims)
    if not dims:
        raise PlotError(
            f"{var} is a single value after --sel ({da.values.item()!s}); leave a dimension to "
            "draw against"
        )
    if x is None:
        rest = [d for d in dims if d != hue]
        x = "s" if "s" in rest else max(rest, key=lambda d: da.sizes[d]) if rest else None
    if x is None:
        raise PlotError(f"--x: choose one of {', '.join(map(str, dims))}")
    rest = [d for d in dims if d not in (x, hue)]
    if hue is None and len(rest) == 1:
        hue, rest = rest[0], []
    if rest:
        raise PlotError(
            f"{var} has more dimensions than x and hue: pick one value of "
            f"{', '.join(map(str, rest))} with --sel DIM=VALUE"
        )
    if x not in da.coords:
        da = da.assign_coords({x: np.arange(da.sizes[x])})
    if hue is not None and hue not in da.coords:
        da = da.assign_coords({hue: np.arange(da.sizes[hue])})
    if da.dtype.kind not in "fiu":
        raise PlotError(f"{var} holds {da.dtype} values, not numbers; nothing to draw")
    marker = "." if da.sizes[x] < 30 else None
    if hue is not None and da.sizes[hue] > MAX_LEGEND:
        _many_curves(fig, ax, da, x, hue, ds)
    else:
        da.plot.line(ax=ax, x=x, hue=hue, marker=marker)
    ax.set_xlabel(_label(ds[x], x) if x in ds.variables else f"{x} [1]")
    ax.set_ylabel(_label(ds[var], var))
    ax.set_title(", ".join(picked) or str(ds.attrs.get("study_name", "")))
    return fig


def plot_result(
    path: str | Path,
    var: str,
    *,
    x: str | None = None,
    hue: str | None = None,
    sel: list[str] | None = None,
    out: str | Path | None = None,
    shape: bool = False,
) -> Path:
    """Draw ``var`` of the result file ``path`` to a PNG and return its path.

    Parameters
    ----------
    path : result file (netCDF)
    var : data variable to draw
    x : dimension on the x axis (default: ``s`` if present, else the last)
    hue : dimension drawn as one curve per value (default: the one left over)
    sel : ``DIM=VALUE`` picks (nearest value for numeric coordinates, index otherwise)
    out : PNG file (default: ``<result stem>-<var>.png`` beside the result)
    shape : draw profiles on ``s`` as line shapes in the x-z plane
    """
    path = Path(path)
    try:
        ds = xr.open_dataset(path)
    except (OSError, ValueError) as exc:
        raise PlotError(f"{path}: cannot open as a result file ({exc})") from None
    with ds:
        fig = quick_look(ds, var, x=x, hue=hue, sel=sel, shape=shape)
        target = Path(out) if out else path.with_name(f"{path.stem}-{var}.png")
        target.parent.mkdir(parents=True, exist_ok=True)
        fig.savefig(target, dpi=120)
    return target
