"""Quick-look plots of a result file: one or several variables of one unit against any
dimension, labelled with their long names and the unit shown (``--units`` converts by
the small table :data:`UNITS`), on matplotlib's Agg backend (no screen). Labelled sweep
axes and swept vectors read as their labels or values, never as an index; long labels
wrap, the layout is constrained and the PNG is cut to a tight bounding box.

``quick_look(ds, var, ...)`` returns the matplotlib figure (tests inspect its labels);
``plot_result(path, var, ...)`` opens a result file and writes a PNG.
"""

from __future__ import annotations

import json
import textwrap
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr


class PlotError(ValueError):
    """A plot that cannot be drawn; the message names the bad name and the valid ones."""


#: units ``--units`` converts between: unit -> (quantity, size in the quantity's SI unit)
UNITS: dict[str, tuple[str, float]] = {
    "N": ("force", 1.0),
    "kN": ("force", 1e3),
    "MN": ("force", 1e6),
    "N/m": ("stiffness", 1.0),
    "kN/m": ("stiffness", 1e3),
    "MN/m": ("stiffness", 1e6),
    "m": ("length", 1.0),
    "mm": ("length", 1e-3),
    "km": ("length", 1e3),
    "s": ("time", 1.0),
    "min": ("time", 60.0),
    "h": ("time", 3600.0),
    "Hz": ("frequency", 1.0),
    "rad/s": ("frequency", 1.0 / (2.0 * np.pi)),
    "rad": ("angle", 1.0),
    "deg": ("angle", np.pi / 180.0),
}

#: characters per line before a label wraps (7 x 4.5 in figure, 10 pt text)
WRAP_TITLE, WRAP_X, WRAP_Y, WRAP_LEGEND = 70, 80, 45, 40


def unit_scale(units: str, shown: str | None, var: str) -> tuple[float, str]:
    """(factor, unit shown): values of ``var`` in ``units`` times the factor are in
    ``shown`` (unchanged when ``shown`` is None). Raises :class:`PlotError` for a unit
    the table does not know or one of another quantity."""
    if shown is None or shown == units:
        return 1.0, units
    known = ", ".join(UNITS)
    if shown not in UNITS:
        raise PlotError(f"--units {shown!r}: unknown unit; known units: {known}")
    quantity, size = UNITS[shown]
    if units not in UNITS:
        raise PlotError(
            f"--units {shown!r}: {var} is in {units!r}, which this table does not convert; "
            f"known units: {known}"
        )
    have, have_size = UNITS[units]
    if have != quantity:
        same = ", ".join(u for u, (q, _) in UNITS.items() if q == have)
        raise PlotError(
            f"--units {shown!r}: {var} is a {have} in {units!r}, which converts to {same} "
            f"only (not to a {quantity})"
        )
    return have_size / size, shown


def _wrap(text: str, width: int) -> str:
    return textwrap.fill(text, width, break_long_words=False, break_on_hyphens=False)


def _label(obj: xr.DataArray, name: str, units: str | None = None) -> str:
    long_name = obj.attrs.get("long_name", name)
    units = obj.attrs.get("units", "1") if units is None else units
    return f"{long_name} [{units}]"


def _is_text(values: np.ndarray) -> bool:
    return values.dtype.kind in "OUS"


def _value_text(ds: xr.Dataset | xr.DataArray, dim: str, k: int) -> str:
    """Value ``k`` of the dimension ``dim`` as a reader wants it: its label, the swept
    vector itself for an index coordinate ("[1, 0, 0]"), or the number with its unit."""
    if dim not in ds.coords:
        return str(k)
    value = ds[dim].values[k]
    if _is_text(ds[dim].values):
        return str(value)
    swept = f"{dim}_value"
    if swept in ds.coords and _is_text(ds[swept].values):
        try:
            return _compact(json.loads(str(ds[swept].values[k])))
        except ValueError:
            return str(ds[swept].values[k])
    units = ds[dim].attrs.get("units", "1")
    return f"{value:g}" + ("" if units in ("1", "") else f" {units}")


def _compact(value: Any) -> str:
    """A swept value (number, list, mapping) in short text: floats as ``g``."""
    if isinstance(value, float):
        return f"{value:g}"
    if isinstance(value, list):
        return "[" + ", ".join(_compact(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{k}: {_compact(v)}" for k, v in value.items()) + "}"
    return str(value)


def _dim_label(ds: xr.Dataset, dim: str) -> str:
    """Axis label of a dimension: long name and unit; no unit for labels or swept
    vectors, whose ticks are texts."""
    if dim not in ds.coords:
        return f"{dim} [1]"
    coord = ds[dim]
    swept = f"{dim}_value"
    if _is_text(coord.values):
        return str(coord.attrs.get("long_name", dim))
    if swept in ds.coords and _is_text(ds[swept].values):
        return f"{dim}: {coord.attrs.get('sweep_paths', dim)}"
    return _label(coord, dim)


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
        swept = f"{dim}_value"
        if value.lstrip().startswith(("[", "{")) and swept in ds.coords:
            # a swept vector by its value: --sel motion=[0,0,1]
            k = _vector_index(ds, dim, value, item)
            da = da.isel({dim: k})
            picked.append(f"{dim} = {_value_text(ds, dim, k)}")
            continue
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
            chosen = da[dim].values.item()
            k = next(i for i, v in enumerate(coord.values.tolist()) if v == chosen)
            picked.append(f"{dim} = {_value_text(ds, dim, k)}")
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


def _vector_index(ds: xr.Dataset, dim: str, value: str, item: str) -> int:
    """Index along ``dim`` of the swept value written as JSON/YAML flow text."""
    try:
        wanted = json.loads(value)
    except ValueError:
        raise PlotError(
            f"--sel {item!r}: write the swept value as a list, e.g. [0, 0, 1]"
        ) from None
    texts = [str(v) for v in ds[f"{dim}_value"].values]
    for k, text in enumerate(texts):
        try:
            if np.allclose(np.asarray(json.loads(text), float), np.asarray(wanted, float)):
                return k
        except (ValueError, TypeError):
            if json.loads(text) == wanted:
                return k
    shown = ", ".join(_value_text(ds, dim, k) for k in range(len(texts)))
    raise PlotError(f"--sel {item!r}: {dim} has no swept value {value}; values: {shown}")


#: more curves than this get a colour bar instead of a legend
MAX_LEGEND = 10
#: line styles that tell variables apart when colours tell the hue values apart
STYLES = ("-", "--", ":", "-.")


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
    label = _dim_label(ds, hue) if numeric and hue in ds.variables else f"{hue} (index)"
    bar.set_label(_wrap(label, WRAP_Y))
    return lambda k: cmap(norm(c[k]))


def _check_dim(name: str | None, flag: str, da: xr.DataArray) -> None:
    if name is not None and name not in da.dims:
        raise PlotError(
            f"{flag} {name!r}: {da.name} has no dimension {name!r} (after --sel); its "
            f"dimensions: {', '.join(map(str, da.dims)) or 'none'}"
        )


def _figure() -> Any:
    import matplotlib

    if "matplotlib.pyplot" not in __import__("sys").modules:
        matplotlib.use("Agg")
    from matplotlib.figure import Figure

    return Figure(figsize=(7.0, 4.5), layout="constrained")


def _shape(
    fig: Any, ax: Any, ds: xr.Dataset, var: str, da: xr.DataArray, **kw: Any
) -> tuple[Any, list[str]]:
    """Profiles on ``s`` drawn as line shapes in the x-z plane."""
    hue, sel, units = kw["hue"], kw["sel"], kw["units"]
    if "s" not in da.dims or "x" not in ds.data_vars or "z" not in ds.data_vars:
        raise PlotError(
            f"--shape draws profiles on s from the variables x and z; {var!r} has "
            f"dimensions {', '.join(map(str, da.dims)) or 'none'}"
        )
    xs, picked = _select(ds["x"], ds, sel)
    zs, _ = _select(ds["z"], ds, sel)
    xs, zs = xs.squeeze(drop=False), zs.squeeze(drop=False)
    factor, shown = unit_scale(str(ds["x"].attrs.get("units", "m")), units, "x")
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
        ax.plot(factor * xs.values.ravel(), factor * zs.values.ravel())
    else:
        many = xs.sizes[hue] > MAX_LEGEND
        colour = _colours(fig, ax, xs, hue, ds) if many else None
        for k in range(xs.sizes[hue]):
            ax.plot(
                factor * xs.isel({hue: k}).values.ravel(),
                factor * zs.isel({hue: k}).values.ravel(),
                label=_wrap(f"{hue} = {_value_text(xs, hue, k)}", WRAP_LEGEND),
                color=colour(k) if colour else None,
            )
        if not many:
            ax.legend(fontsize="small")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(_wrap(_label(ds["x"], "x", shown), WRAP_X))
    ax.set_ylabel(_wrap(_label(ds["z"], "z", shown), WRAP_Y))
    return fig, picked


def _same_units(ds: xr.Dataset, names: Sequence[str]) -> str:
    """The unit the variables ``names`` share; refuses two that differ, naming both."""
    first = names[0]
    units = str(ds[first].attrs.get("units", "1"))
    for other in names[1:]:
        theirs = str(ds[other].attrs.get("units", "1"))
        if theirs != units:
            raise PlotError(
                f"{first} is in {units!r} and {other} in {theirs!r}: variables drawn on "
                "one axes must share their unit; draw them in separate plots"
            )
    return units


def quick_look(
    ds: xr.Dataset,
    var: str | Sequence[str],
    *,
    x: str | None = None,
    hue: str | None = None,
    sel: list[str] | None = None,
    shape: bool = False,
    units: str | None = None,
) -> Any:
    """A matplotlib figure of ``ds[var]`` (see :func:`plot_result` for the arguments)."""
    names = [var] if isinstance(var, str) else list(var)
    if not names:
        raise PlotError("name at least one variable to draw")
    for name in names:
        if name not in ds.data_vars:
            raise PlotError(
                f"no variable {name!r} in the result; variables: "
                f"{', '.join(sorted(map(str, ds.data_vars)))}"
            )
    twice = sorted({n for n in names if names.count(n) > 1})
    if twice:
        raise PlotError(f"{', '.join(twice)} named twice; name each variable once")
    sel = sel or []
    fig = _figure()
    ax = fig.add_subplot()
    study = str(ds.attrs.get("study_name", ""))
    if shape:
        if len(names) > 1:
            raise PlotError(f"--shape draws one line shape; got {len(names)} variables")
        da, _ = _select(ds[names[0]], ds, sel)
        fig, picked = _shape(
            fig, ax, ds, names[0], da.squeeze(drop=False), hue=hue, sel=sel, units=units
        )
        ax.set_title(_wrap(", ".join(picked) or study, WRAP_TITLE))
        return fig
    common = _same_units(ds, names)
    factor, shown = unit_scale(common, units, names[0])
    arrays = []
    for name in names:
        da, picked = _select(ds[name], ds, sel)
        arrays.append(da.squeeze(drop=False))
    da = arrays[0]
    for name, other in zip(names[1:], arrays[1:], strict=True):
        if set(other.dims) != set(da.dims):
            raise PlotError(
                f"{names[0]} has dimensions ({', '.join(map(str, da.dims))}) and {name} "
                f"({', '.join(map(str, other.dims))}) after --sel; variables drawn on one "
                "axes must share their dimensions"
            )
    arrays = [a.transpose(*da.dims) for a in arrays]
    _check_dim(x, "--x", da)
    _check_dim(hue, "--hue", da)
    dims = list(da.dims)
    if not dims:
        raise PlotError(
            f"{names[0]} is a single value after --sel ({da.values.item()!s}); leave a "
            "dimension to draw against"
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
            f"{names[0]} has more dimensions than x and hue: pick one value of "
            f"{', '.join(map(str, rest))} with --sel DIM=VALUE"
        )
    for name, arr in zip(names, arrays, strict=True):
        if arr.dtype.kind not in "fiu":
            raise PlotError(f"{name} holds {arr.dtype} values, not numbers; nothing to draw")
    _draw(fig, ax, ds, names, arrays, x=x, hue=hue, factor=factor)
    ax.set_xlabel(_wrap(_dim_label(ds, x), WRAP_X))
    if len(names) == 1:
        ylabel = _label(ds[names[0]], names[0], shown)
    else:
        ylabel = f"{_joined([str(ds[n].attrs.get('long_name', n)) for n in names])} [{shown}]"
    ax.set_ylabel(_wrap(ylabel, WRAP_Y))
    ax.set_title(_wrap(", ".join(picked) or study, WRAP_TITLE))
    return fig


def _draw(
    fig: Any,
    ax: Any,
    ds: xr.Dataset,
    names: list[str],
    arrays: list[xr.DataArray],
    *,
    x: str,
    hue: str | None,
    factor: float,
) -> None:
    """The curves: one per variable and ``hue`` value. Colours tell the hue values apart
    (a colour bar for many), line styles the variables; the legend names both."""
    from matplotlib.lines import Line2D

    n = arrays[0].sizes[x]
    xcoord = arrays[0][x].values if x in arrays[0].coords else np.arange(n)
    text_ticks = _is_text(xcoord) or (
        f"{x}_value" in ds.coords and _is_text(ds[f"{x}_value"].values)
    )
    xs = np.arange(n) if text_ticks else xcoord
    if text_ticks:
        ax.set_xticks(xs, [_value_text(arrays[0], x, k) for k in range(n)])
    marker = "." if n < 30 else None
    n_hue = arrays[0].sizes[hue] if hue is not None else 1
    many = hue is not None and n_hue > MAX_LEGEND
    colour = _colours(fig, ax, arrays[0], hue, ds) if many else None
    several = len(names) > 1
    handles = []
    for j, (name, arr) in enumerate(zip(names, arrays, strict=True)):
        style = STYLES[j % len(STYLES)] if several and hue is not None else "-"
        for k in range(n_hue):
            y = arr.isel({hue: k}) if hue is not None else arr
            if hue is None:
                ax.plot(xs, factor * y.values, marker=marker, label=_var_name(ds, name))
                continue
            c = colour(k) if colour else f"C{k % 10}"
            line = ax.plot(xs, factor * y.values, style, color=c, marker=marker, lw=1.2)[0]
            if not several and not many:
                line.set_label(_wrap(f"{hue} = {_value_text(arr, hue, k)}", WRAP_LEGEND))
        if hue is not None and several:
            handles.append(Line2D([], [], color="k", ls=style, label=_var_name(ds, name)))
    if hue is not None and several and not many:
        handles += [
            Line2D([], [], color=f"C{k % 10}", label=f"{hue} = {_value_text(arrays[0], hue, k)}")
            for k in range(n_hue)
        ]
    if handles:
        ax.legend(handles=handles, fontsize="small")
    elif several or (hue is not None and not many):
        ax.legend(fontsize="small")


def _joined(long_names: list[str]) -> str:
    """Long names joined on what differs: "tension at end A / B", "maximum / minimum
    tension at the excited end"."""
    words = [n.split() for n in long_names]
    head = 0
    while all(len(w) > head + 1 and w[head] == words[0][head] for w in words):
        head += 1
    tail = 0
    while all(len(w) > head + tail + 1 and w[-1 - tail] == words[0][-1 - tail] for w in words):
        tail += 1
    middles = [" ".join(w[head : len(w) - tail]) for w in words]
    parts = [*words[0][:head], " / ".join(middles), *words[0][len(words[0]) - tail :]]
    return " ".join(parts)


def _var_name(ds: xr.Dataset, name: str) -> str:
    return _wrap(str(ds[name].attrs.get("long_name", name)), WRAP_LEGEND)


def plot_result(
    path: str | Path,
    var: str | Sequence[str],
    *,
    x: str | None = None,
    hue: str | None = None,
    sel: list[str] | None = None,
    out: str | Path | None = None,
    shape: bool = False,
    units: str | None = None,
) -> Path:
    """Draw ``var`` (one or several variables of one unit) of the result file ``path`` to
    a PNG and return its path.

    Parameters
    ----------
    path : result file (netCDF)
    var : data variable(s) to draw on one axes
    x : dimension on the x axis (default: ``s`` if present, else the longest)
    hue : dimension drawn as one curve per value (default: the one left over)
    sel : ``DIM=VALUE`` picks (nearest value for numeric coordinates, the label for
        text ones, index where a dimension has no coordinate)
    out : PNG file (default: ``<result stem>-<var>.png`` beside the result)
    shape : draw profiles on ``s`` as line shapes in the x-z plane
    units : unit of the values drawn, from :data:`UNITS` (default: the file's, SI)
    """
    names = [var] if isinstance(var, str) else list(var)
    path = Path(path)
    try:
        ds = xr.open_dataset(path)
    except (OSError, ValueError) as exc:
        raise PlotError(f"{path}: cannot open as a result file ({exc})") from None
    with ds:
        fig = quick_look(ds, names, x=x, hue=hue, sel=sel, shape=shape, units=units)
        stem = "-".join(names)
        target = Path(out) if out else path.with_name(f"{path.stem}-{stem}.png")
        target.parent.mkdir(parents=True, exist_ok=True)
        # constrained layout keeps the texts in the figure; tight bbox is the safety net
        fig.savefig(target, dpi=120, bbox_inches="tight", pad_inches=0.05)
    return target
