"""The package versions a dataset records are the strings importlib.metadata gives."""

from __future__ import annotations

from importlib.metadata import version

import pytest

from cablestudy.run.dataset import installed_version


@pytest.mark.parametrize("name", ["scipy", "xarray", "dask", "numpy", "pydantic", "netCDF4"])
def test_installed_version_is_importlib_metadatas(name: str) -> None:
    # scipy's metadata holds its licences after the headers: the header is read alone
    assert installed_version(name) == version(name)
