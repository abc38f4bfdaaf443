"""Paper figures: one builder per figure, reading results datasets.

:data:`FIGURES` maps a figure name to (the study names it reads, builder). ``build_all``
runs any missing study from ``configs/`` (unless told not to), and any whose result was
made from another text of its config (its ``study_sha256``), and writes PNGs.
"""

from __future__ import annotations

from pathlib import Path

import xarray as xr

from .registry import FIGURES


class MissingResult(FileNotFoundError):
    """A figure needs a result file that is not there and may not be made here."""


def _stale(path: Path, config: Path) -> bool:
    """True when the result ``path`` was made from another text than ``config`` (its
    ``study_sha256`` differs from the config's): a figure from it would silently show
    the study as it was, not as it is."""
    from ..study.loader import read_study_source

    with xr.open_dataset(path) as ds:
        made_from = ds.attrs.get("study_sha256")
    return made_from != read_study_source(config).sha256


def _ensure_study(name: str, results: Path, configs: Path, run_missing: bool) -> Path:
    path = results / f"{name}.nc"
    config = configs / f"{name}.yaml"
    stale = path.exists() and config.is_file() and _stale(path, config)
    if path.exists() and not stale:
        return path
    if not run_missing:
        why = f"was made from another version of {config}" if stale else "is missing"
        raise MissingResult(
            f"{path} {why}; make it with `cablestudy run {configs / name}.yaml --out "
            f"{results}`, or run `cablestudy figures` without --no-run"
        )
    from ..analyses.evaluate import check_supported
    from ..run.runner import run_study
    from ..study.grid import expand_grid
    from ..study.loader import read_study_source

    candidates = [p for p in sorted(configs.glob("*.yaml")) if p.stem == name]
    if not candidates:
        raise MissingResult(f"{path} is missing and there is no {configs / name}.yaml to run")
    src = read_study_source(candidates[0])
    grid = expand_grid(src)
    check_supported(grid.cases(), src)
    run_study(src, grid, results, scheduler="synchronous" if grid.size <= 8 else "processes")
    return path


def build_all(
    results: Path,
    out: Path,
    *,
    configs: Path = Path("configs"),
    run_missing: bool = True,
    only: list[str] | None = None,
    docs: Path | None = None,
) -> list[Path]:
    """Build every registered figure (or those in ``only``); returns the PNG paths.

    With ``docs``, also copy the figures to ``docs/figures/`` and write the checked
    gallery ``docs/validation.md`` (:mod:`.gallery`)."""
    import matplotlib

    matplotlib.use("Agg")
    from . import (  # noqa: F401  (each module registers its builders)
        dynamics_figures,
        modal_figures,
        statics_figures,
        umbilical_figures,
        vaz_patel_figures,
    )

    out.mkdir(parents=True, exist_ok=True)
    written = []
    for name, (studies, builder) in sorted(FIGURES.items()):
        if only is not None and name not in only:
            continue
        datasets = {}
        for study in studies:
            path = _ensure_study(study, results, configs, run_missing)
            datasets[study] = xr.load_dataset(path)
        written.append(builder(datasets, out))
    if docs is not None:
        import shutil

        from .gallery import gallery_markdown, studies_needed

        data = {
            name: xr.load_dataset(_ensure_study(name, results, configs, run_missing))
            for name in studies_needed()
        }
        images = docs / "figures"
        images.mkdir(parents=True, exist_ok=True)
        copied = []
        for path in written:
            shutil.copyfile(path, images / path.name)
            copied.append(images / path.name)
        (docs / "validation.md").write_text(gallery_markdown(data, copied, "figures"))
        written.append(docs / "validation.md")
    return written
