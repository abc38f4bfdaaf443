"""Atomic netCDF writes: a temporary file in the target's folder, fsync, the
permissions of a new file, then a rename, so that a crash never leaves a half-written
result; float variables compressed where it pays (:func:`worth_compressing`), none in a
small result (:func:`small_result`).
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from .conventions import is_status_variable, status_flag_attrs
from .outputs import temporary_prefix, written

if TYPE_CHECKING:  # imported where used: a sweep run as arrays writes without xarray
    import xarray as xr


def _umask() -> int:
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def _atomically(path: str | Path, write: Any) -> Path:
    """Call ``write(tmp)`` on a temporary file in ``path``'s folder, then fsync it, give it
    the permissions of a new file and rename it to ``path`` (atomic): a crash never
    leaves a half-written or corrupted result. The temporary file's name holds this
    process's id (:func:`cablestudy.run.outputs.temporary_prefix`): a later run removes it
    if this one is killed while writing. A full disk raises
    :class:`cablestudy.run.outputs.OutputWriteError`."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(
        prefix=temporary_prefix(f".{path.name}."), suffix=".tmp", dir=path.parent
    )
    os.close(fd)

    def complete() -> None:
        write(tmp)
        with open(tmp, "rb+") as fh:  # on disk before the rename makes it visible
            os.fsync(fh.fileno())
        os.chmod(tmp, 0o666 & ~_umask())  # mkstemp makes it private (0600)
        os.replace(tmp, path)

    try:
        written(path, complete)  # a full disk named as such, whoever reports it
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)
    return path


#: netCDF compression of a floating-point data variable that is worth it (coordinates
#: are never compressed)
FLOAT_ENCODING: dict[str, Any] = {"zlib": True, "complevel": 1, "shuffle": True}
#: an in-memory variable is compressed when samples of it (SAMPLE_BLOCKS blocks of
#: SAMPLE_BYTES, evenly spaced) shrink to at most COMPRESS_BELOW of their size: a
#: constant or mostly-NaN variable shrinks a hundredfold, while the smooth profiles of a
#: sweep shrink by a third at a cost that exceeds their solve (zlib runs at some 100 MB/s,
#: the batch kernel at about 1 GB of output a second). (Blocks of 4 KiB would judge at
#: half the cost, but differently: 53 of the 1322 variables of configs/ flipped.)
COMPRESS_BELOW = 0.5
SAMPLE_BYTES = 1 << 14
SAMPLE_BLOCKS = 4


#: a result whose in-memory float data variables hold fewer bytes than this is written
#: uncompressed: compressing could save less than this of the file, while judging each
#: variable (a zlib pass over its samples) and compressing it (another) cost a small
#: study more than its solve (a 50-case system sweep: 5 of its 60 ms, for 0.4 MB)
SMALL_RESULT_BYTES = 4 << 20


def small_result(arrays: Any) -> bool:
    """Whether a result whose float data variables are ``arrays`` is small enough to be
    written uncompressed (:data:`SMALL_RESULT_BYTES`): every one of them a NumPy array (a
    lazily computed one is streamed, and compressed) and their bytes summed under it."""
    total = 0
    for values in arrays:
        if not isinstance(values, np.ndarray):
            return False
        total += values.nbytes
    return total < SMALL_RESULT_BYTES


def worth_compressing(values: Any) -> bool:
    """Whether to store the float variable ``values`` zlib-compressed: always for a
    lazily computed (dask) one, which is streamed in blocks; for a NumPy array, when
    byte-shuffled samples of it compress to at most :data:`COMPRESS_BELOW`."""
    import zlib

    if not isinstance(values, np.ndarray):
        return True
    flat = np.ascontiguousarray(values).reshape(-1)
    if flat.size == 0:
        return False
    block = max(1, SAMPLE_BYTES // flat.itemsize)
    starts = np.unique(np.linspace(0, max(flat.size - block, 0), SAMPLE_BLOCKS).astype(int))
    sample = np.concatenate([flat[i : i + block] for i in starts])
    raw = sample.view(np.uint8).reshape(-1, sample.itemsize).T.tobytes()  # as HDF5 shuffles
    return len(zlib.compress(raw, 1)) <= COMPRESS_BELOW * len(raw)


def write_atomic(ds: xr.Dataset, path: str | Path) -> Path:
    """Write ``ds`` to netCDF at ``path`` through a temporary file in the same folder and
    an atomic rename: a crash never leaves a half-written or corrupted result."""
    ds = ds.copy()
    for name, v in ds.data_vars.items():
        if is_status_variable(str(name)) and v.dtype.kind in "if":
            v.attrs.update(status_flag_attrs(v.dtype))
    floats = {name: v for name, v in ds.data_vars.items() if v.dtype.kind == "f"}
    small = small_result(v.values if v.chunks is None else v.data for v in floats.values())
    encoding: dict[str, dict[str, Any]] = {
        name: dict(FLOAT_ENCODING)
        for name, v in floats.items()
        if not small and worth_compressing(v.values if v.chunks is None else v.data)
    }
    for name, v in ds.data_vars.items():
        if v.chunks is not None and name in encoding:
            # variables streamed from chunk files (dask): netCDF chunks of one block
            # of cases (at most 4 MiB), so that reading one case touches little
            block = [c[0] for c in v.chunks]
            per_case = max(1, int(np.prod(block[1:])) * v.dtype.itemsize)
            block[0] = max(1, min(block[0], (4 << 20) // per_case))
            encoding[name]["chunksizes"] = tuple(block)
    return _atomically(path, lambda tmp: ds.to_netcdf(tmp, engine="netcdf4", encoding=encoding))


def _put_whole(var: Any, values: np.ndarray) -> None:
    """Write all of ``values`` (of ``var``'s shape and dtype, or objects for text) into the
    netCDF variable ``var``: what ``var[...] = values`` ends in (netCDF4's ``_put`` of the
    whole extent, one ``nc_put_vara``), without the slice analysis and the attribute
    look-ups (``scale_factor``, ``add_offset``) before it, which cost 40-60 us a variable
    (2 ms of a system sweep's 46); by indexing where that method is absent, or the
    variable has no dimension or no value."""
    put = getattr(var, "_put", None)
    if put is None or values.size == 0 or values.ndim == 0 or values.shape != var.shape:
        var[...] = values
        return
    ndim = values.ndim
    put(
        np.ascontiguousarray(values),
        np.zeros(ndim, dtype=np.intp),
        np.array(values.shape, dtype=np.intp),
        np.ones(ndim, dtype=np.intp),
    )


#: a variable as (dims, values, attrs), the tuple form xarray.Dataset takes
VariableSpec = tuple[Any, Any, dict[str, Any]]


def write_variables_atomic(
    data_vars: dict[str, VariableSpec],
    coords: dict[str, VariableSpec],
    attrs: dict[str, Any],
    path: str | Path,
) -> Path:
    """Write the dataset ``xarray.Dataset(data_vars, coords=coords, attrs=attrs)`` of
    in-memory NumPy arrays to netCDF at ``path`` (atomically, as :func:`write_atomic`),
    with the netCDF4 library directly: the file :func:`write_atomic` writes (the same
    dimensions, variables in the same order, dtypes, attributes, ``_FillValue`` and
    compression), without importing xarray (and the dask and distributed modules it
    loads when they are installed), which costs a small study more than its solve. A
    dataset this writer does not cover (a non-dimension coordinate, which xarray links
    through a ``coordinates`` attribute; a dtype other than float, int and text) goes
    through xarray."""
    items = [
        (k, (v[0],) if isinstance(v[0], str) else tuple(v[0]), v[1], v[2])
        for k, v in data_vars.items()
    ]
    items += [
        (k, (v[0],) if isinstance(v[0], str) else tuple(v[0]), v[1], v[2])
        for k, v in coords.items()
    ]
    simple = all(dims == (k,) for k, dims, _, _ in items[len(data_vars) :]) and all(
        isinstance(values, np.ndarray) and values.dtype.kind in "fiuUO" for _, _, values, _ in items
    )
    if not simple:
        import xarray as xr

        return write_atomic(xr.Dataset(data_vars, coords=coords, attrs=attrs), path)

    small = small_result(v for _, _, v, _ in items[: len(data_vars)] if v.dtype.kind == "f")

    def write(tmp: str) -> None:
        import netCDF4

        with netCDF4.Dataset(tmp, mode="w", clobber=True, format="NETCDF4") as nc:
            for key, value in attrs.items():
                nc.setncattr(key, value)
            for _name, dims, values, _ in items:  # dimensions in order of first use
                for dim, size in zip(dims, values.shape, strict=True):
                    if dim not in nc.dimensions:
                        nc.createDimension(dim, size)
            defined = []
            for i, (name, dims, values, var_attrs) in enumerate(items):
                kind = values.dtype.kind
                text = kind in "UO"
                compress = (
                    kind == "f" and i < len(data_vars) and not small and worth_compressing(values)
                )
                encoding = FLOAT_ENCODING if compress else {}
                var = nc.createVariable(
                    varname=name,
                    datatype=str if text else values.dtype,
                    dimensions=dims,
                    zlib=encoding.get("zlib", False),
                    complevel=encoding.get("complevel", 4),
                    shuffle=encoding.get("shuffle", True),
                    fletcher32=False,
                    contiguous=False,
                    chunksizes=None,
                    endian="native",
                    least_significant_digit=None,
                    fill_value=np.nan if kind == "f" else None,
                )
                if i < len(data_vars) and is_status_variable(name) and kind in "if":
                    var_attrs = {**var_attrs, **status_flag_attrs(values.dtype)}
                var.setncatts(var_attrs)
                var.set_auto_maskandscale(False)
                var.set_auto_chartostring(False)
                defined.append((var, values.astype(object) if text else values))
            # the values only once every variable is defined: a write ends netCDF's
            # define mode and the next definition re-enters it, and each return to data
            # mode rewrites the file's metadata (all of it: the 46 variables of a system
            # sweep cost 17 ms written one by one after its definition, 7 ms so)
            for var, values in defined:
                _put_whole(var, values)

    return _atomically(path, write)
