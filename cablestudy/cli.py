"""Command line: ``cablestudy run | validate | schema | figures | bench | import | export |
plot``."""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Callable
from pathlib import Path


def _size(text: str) -> int:
    from .study.safe_yaml import parse_size

    try:
        return parse_size(text)
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def _load(path: str, max_bytes: int | None = None):  # noqa: ANN202
    """The study source and its grid of cases (:func:`cablestudy.run.grid_runner.study_grid`),
    every case checked against what the solvers support before any work."""
    from .analyses.evaluate import check_supported
    from .run.grid_runner import study_grid
    from .study.cases import Case, case_hashes
    from .study.grid_studies import axis_studies
    from .study.loader import read_study_source

    src = read_study_source(path, max_bytes=max_bytes)
    for note in src.notes:
        print(f"warning: {note}", file=sys.stderr)
    grid = study_grid(src)
    if not grid.chunked:
        check_supported(grid.cases(), src)
    elif grid.arrays and grid.template.analysis.static.method == "catenary":
        # a catenary array grid sweeps numbers only (end positions, stiffnesses, lengths,
        # loads, attachments, current, settings, coefficients, limits; study.grid._eligible),
        # each validated at its own path as the grid is built; what the support checks read
        # (end kinds, law kinds, pulleys, analyses) is the template's in every case, so the
        # template answers for all (and 300 axis studies cost 20 ms of a 0.5 s run)
        check_supported([Case((), {}, grid.template, *case_hashes(grid.template))], src)
    else:
        studies = axis_studies(grid)
        check_supported([Case((), {}, st, *case_hashes(st)) for st in studies], src)
    return src, grid.axes, grid


def cmd_validate(args: argparse.Namespace) -> int:
    src, axes, grid = _load(args.config, args.max_study_size)
    dims = ", ".join(f"{a.name}={a.size}" for a in axes) or "no sweep"
    print(f"{args.config}: valid study {src.data['name']!r}: {grid.size} cases ({dims})")
    if grid.whole:
        print(
            "  validated as whole studies, once per combination of their values (they "
            f"cannot be copied into the validated template): {', '.join(grid.whole)}"
        )
    return 0


class _Terminated(list):
    """Whether SIGTERM arrived (truthy once it did), and the handler it replaced."""

    previous: object = None

    def restore(self) -> None:
        if self.previous is not None:
            import signal

            signal.signal(signal.SIGTERM, self.previous)


def _on_sigterm() -> _Terminated:
    """Make SIGTERM stop a run as Ctrl-C does (finished cases cached, one line said,
    exit 143 instead of dying silently); returns the flag the handler sets. Only in the
    main thread, where Python delivers signals."""
    import signal
    import threading

    flag = _Terminated()
    if threading.current_thread() is not threading.main_thread():
        return flag

    def stop(signum: int, frame: object) -> None:
        flag.append(signum)
        raise KeyboardInterrupt

    flag.previous = signal.signal(signal.SIGTERM, stop)
    return flag


def cmd_run(args: argparse.Namespace) -> int:
    from .run.outputs import OutputPathError, OutputWriteError, check_output_paths
    from .run.remote import (
        SchedulerAddressError,
        SchedulerUnreachable,
        connect,
        connect_timeout,
        parse_address,
    )
    from .run.runner import run_study
    from .run.scheduler import AUTO, SCHEDULERS

    scheduler = args.scheduler or AUTO
    if scheduler not in SCHEDULERS and "://" not in scheduler:
        print(
            f"--scheduler {scheduler!r}: allowed are {', '.join(SCHEDULERS)} or the address "
            "of a running dask.distributed scheduler (tcp://host:port)",
            file=sys.stderr,
        )
        return 2
    try:
        timeout = connect_timeout(args.connect_timeout)
        if "://" in scheduler:
            parse_address(scheduler)
    except SchedulerAddressError as exc:
        print(exc, file=sys.stderr)
        return 2
    src, axes, grid = _load(args.config, args.max_study_size)
    # before any work: the output folder can take the result, the scheduler answers
    try:
        check_output_paths(Path(args.out), str(src.data["name"]), cache=not args.no_cache)
    except OutputPathError as exc:
        print(exc, file=sys.stderr)
        return 2
    if "://" in scheduler:
        try:
            connect(scheduler, timeout).close()
        except SchedulerUnreachable as exc:
            print(exc, file=sys.stderr)
            return 1
    from .kernels import ensure_compiled, kinds_of

    studies = [c.study for c in grid.cases()] if not grid.chunked else [grid.template]
    try:
        ensure_compiled(sorted({k for study in studies for k in kinds_of(study)}))
    except KeyboardInterrupt:
        print("\ninterrupted while compiling the kernels: no case was run", file=sys.stderr)
        return 130
    terminated = _on_sigterm()
    try:
        if not grid.chunked:  # the kernels its cases need, loaded before any is timed
            from .analyses.evaluate import warm_up

            warm_up(grid.cases())
        _resume_collection()
        summary = run_study(
            src,
            grid,
            args.out,
            scheduler=scheduler,
            workers=args.workers,
            use_cache=not args.no_cache,
            progress=args.progress,
            timeout=timeout,
        )
    except KeyboardInterrupt:
        how = "terminated" if terminated else "interrupted"
        print(
            f"\n{how}: finished cases are cached; run the same command again to resume",
            file=sys.stderr,
        )
        return 143 if terminated else 130
    except SchedulerUnreachable as exc:
        print(f"{exc}; finished cases are cached", file=sys.stderr)
        return 1
    except OutputWriteError as exc:
        print(f"cannot write the results: {exc.strerror}", file=sys.stderr)
        return 1
    except OSError as exc:  # the machine's state (permissions, I/O): one line, no traceback
        where = f" at {exc.filename}" if exc.filename else ""
        print(f"cannot write the results: {exc.strerror or exc}{where}", file=sys.stderr)
        return 1
    finally:
        terminated.restore()
    print(summary.report())
    if summary.n_failed < summary.n_cases:
        # the summary counts every case of status != 0 (a broken line too) at each place
        # of the grid, so the file's cases_failed is fewer than its cases: no need to
        # open the file again (a few ms)
        return 0
    return _run_status(summary.path)


#: exit status of a run that wrote its dataset but in which no case succeeded: every
#: case failed (``cases_failed`` = ``cases``; each one's status and message say why).
#: A run where some cases succeeded exits 0, its failures recorded (docs/guide/cli.md)
EXIT_NO_CASE_SUCCEEDED = 3


def _run_status(path: Path) -> int:
    """0, or :data:`EXIT_NO_CASE_SUCCEEDED` when the dataset at ``path`` counts every
    case failed (a line broken in statics is an answer, not a failure: ``cases_broken``)."""
    import netCDF4

    with netCDF4.Dataset(path) as nc:
        cases, failed = int(nc.getncattr("cases")), int(nc.getncattr("cases_failed"))
    if cases == 0 or failed < cases:
        return 0
    print(
        f"no case succeeded: all {cases} failed (status and message in {path}); "
        f"exit status {EXIT_NO_CASE_SUCCEEDED}",
        file=sys.stderr,
    )
    return EXIT_NO_CASE_SUCCEEDED


def cmd_compile(args: argparse.Namespace) -> int:
    import time

    from .kernels import KINDS, compile_all

    t0 = time.perf_counter()
    kinds = ", ".join(label for label, _ in KINDS.values())
    print(f"compiling {kinds} (once per install) ...", flush=True)
    seconds = compile_all(jobs=args.jobs)
    each = ", ".join(f"{kind} {t:.1f} s" for kind, t in seconds.items())
    print(f"compiled in {time.perf_counter() - t0:.1f} s ({each})")
    return 0


def cmd_schema(args: argparse.Namespace) -> int:
    from .study import Study

    schema = {
        "$schema": "https://json-schema.org/draft/2020-12/schema",
        "title": "cablestudy study file",
        **Study.model_json_schema(),
    }
    schema["title"] = "cablestudy study file"
    print(json.dumps(schema, indent=2))
    return 0


def cmd_figures(args: argparse.Namespace) -> int:
    from .figures import MissingResult, build_all

    try:
        written = build_all(
            Path(args.results),
            Path(args.out),
            configs=Path(args.configs),
            run_missing=not args.no_run,
            docs=Path(args.docs) if args.docs else None,
        )
    except MissingResult as exc:
        print(f"cannot build the figures: {exc}", file=sys.stderr)
        return 1
    for path in written:
        print(path)
    return 0


def cmd_bench(args: argparse.Namespace) -> int:
    from .bench import run_benchmarks

    only = args.only.split(",") if args.only else None
    readme = Path(args.readme) if args.readme else None
    docs = Path(args.docs) if args.docs else None
    print(run_benchmarks(Path(args.out), quick=args.quick, only=only, readme=readme, docs=docs))
    return 0


def _add_size_option(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "--max-study-size",
        type=_size,
        default=None,
        metavar="SIZE",
        help="refuse study files larger than this (bytes, or 512k, 4M, 1G; default: "
        "$CABLESTUDY_MAX_STUDY_SIZE, else 1M)",
    )


def cmd_import(args: argparse.Namespace) -> int:
    import re

    from .interchange import InterchangeError, import_model, imported_yaml, read_in_scope
    from .interchange.moorpy_yaml import is_mooring_yaml

    try:
        text, path = read_in_scope(args.file, None)
        if args.format == "moorpy" and not is_mooring_yaml(text):
            raise InterchangeError(
                f"{args.file}: not a RAFT/MoorPy mooring YAML (a mapping 'mooring:' with "
                "points, lines and line_types)"
            )
        name = args.name or re.sub(r"[^A-Za-z0-9_.\-]", "-", path.stem).lstrip("-._") or "imported"
        imported = import_model(text, args.file, lines=args.line, name=name, folder=path.parent)
    except InterchangeError as exc:
        print(f"cannot import: {exc}", file=sys.stderr)
        return 2
    if imported.warnings:
        print(f"{args.file}: not modelled by cablestudy (not imported):", file=sys.stderr)
        for w in imported.warnings:
            print(f"  - {w}", file=sys.stderr)
    sys.stdout.write(imported_yaml(imported, args.file))
    return 0


def cmd_export(args: argparse.Namespace) -> int:
    from .interchange import InterchangeError
    from .interchange.case_export import export_case
    from .study.loader import read_study_source

    src = read_study_source(args.config)
    for note in src.notes:
        print(f"warning: {note}", file=sys.stderr)
    try:
        exported = export_case(src, args.case or [])
    except InterchangeError as exc:
        print(f"cannot export: {exc}", file=sys.stderr)
        return 2
    for w in exported.warnings:
        print(f"warning: {w}", file=sys.stderr)
    if exported.extra_files and not args.out:
        print(
            f"cannot export: the file reads {', '.join(exported.extra_files)} beside it; "
            "give --out FILE so they can be written in the same folder",
            file=sys.stderr,
        )
        return 2
    if args.out:
        out = Path(args.out)
        out.parent.mkdir(parents=True, exist_ok=True)
        out.write_text(exported.text)
        for name, text in exported.extra_files.items():
            (out.parent / name).write_text(text)
        print(out)
    else:
        sys.stdout.write(exported.text)
    return 0


def cmd_plot(args: argparse.Namespace) -> int:
    from .plotting import PlotError, plot_result

    try:
        out = plot_result(
            args.result,
            args.var,
            x=args.x,
            units=args.units,
            hue=args.hue,
            sel=args.sel or [],
            out=args.out,
            shape=args.shape,
        )
    except PlotError as exc:
        print(f"cannot plot: {exc}", file=sys.stderr)
        return 2
    print(out)
    return 0


def cmd_line_types(args: argparse.Namespace) -> int:
    from .study.line_types import listing

    sys.stdout.write(listing(args.diameter))
    return 0


def build_parser(command: str | None = None) -> argparse.ArgumentParser:
    """The command line's parser; with ``command`` (a run's first argument) that
    command's sub-parser alone, the others not built (all of them cost a run about 1.5
    ms), or every one where ``command`` names none."""
    from . import __version__

    parser = argparse.ArgumentParser(prog="cablestudy", description=__doc__)
    parser.add_argument("--version", action="version", version=f"cablestudy {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)
    built: list[str] = []

    def add(name: str, **kwargs: str) -> argparse.ArgumentParser | None:
        if command is not None and name != command:
            return None
        built.append(name)
        return sub.add_parser(name, **kwargs)

    if p := add("run", help="run a study file and write <out>/<name>.nc"):
        p.add_argument("config")
        p.add_argument("--out", default="results", help="output folder (default: results)")
        p.add_argument(
            "--workers",
            type=int,
            default=None,
            help="local worker processes (default: the cores available)",
        )
        p.add_argument(
            "--scheduler",
            default=None,
            help="auto | synchronous | threads | processes | tcp://host:port of a "
            "running dask.distributed scheduler (default: auto: run here, and "
            "start --workers processes when the study would take more than a "
            "few seconds)",
        )
        p.add_argument(
            "--connect-timeout",
            type=float,
            default=None,
            metavar="SECONDS",
            help="with --scheduler tcp://host:port: seconds allowed for the scheduler's "
            "handshake, and again for a worker to be there (default: "
            "$CABLESTUDY_CONNECT_TIMEOUT, else 10)",
        )
        p.add_argument("--no-cache", action="store_true", help="recompute every case")
        p.add_argument(
            "--progress",
            action=argparse.BooleanOptionalAction,
            default=None,
            help="progress bar (default: on a terminal)",
        )
        _add_size_option(p)
        p.set_defaults(func=cmd_run)

    if p := add(
        "compile",
        help="compile the numba kernels now (make install does), so that no study waits for it",
    ):
        p.add_argument(
            "--jobs", type=int, default=None, help="processes at once (default: the cores)"
        )
        p.set_defaults(func=cmd_compile)

    if p := add("validate", help="check a study file without running it"):
        p.add_argument("config")
        _add_size_option(p)
        p.set_defaults(func=cmd_validate)

    if p := add("schema", help="print the JSON Schema of study files"):
        p.set_defaults(func=cmd_schema)

    if p := add("figures", help="build the paper figures from results datasets"):
        p.add_argument("--results", default="results")
        p.add_argument("--out", default="results/figures")
        p.add_argument("--configs", default="configs")
        p.add_argument("--no-run", action="store_true", help="do not run missing studies")
        p.add_argument(
            "--docs",
            default=None,
            help="also write the checked gallery DOCS/validation.md with the figures in "
            "DOCS/figures/",
        )
        p.set_defaults(func=cmd_figures)

    if p := add("bench", help="run time against error benchmarks"):
        p.add_argument("--out", default="results/bench")
        p.add_argument("--quick", action="store_true", help="fewer repeats and settings")
        p.add_argument("--only", default=None, help="comma-separated benchmark modules (wp_*)")
        p.add_argument("--readme", default=None, help="README to update between bench markers")
        p.add_argument("--docs", default=None, help="folder for the committed plots")
        p.set_defaults(func=cmd_bench)

    if p := add("import", help="write a study (YAML, to stdout) from another tool's model file"):
        p.add_argument(
            "format",
            choices=["moordyn", "moorpy"],
            help="moordyn: a MoorDyn input file (v1 or v2); moorpy: a RAFT/MoorPy mooring YAML "
            "(either is also detected from the file's content)",
        )
        p.add_argument("file")
        p.add_argument(
            "--line",
            action="append",
            default=None,
            help="a line ID (MoorDyn) or name (mooring YAML) of the line, end to end; repeat "
            "for a line of several (default: all lines: one line where they form one chain, "
            "else one system study of every line, point and body)",
        )
        p.add_argument("--name", default=None, help="study name (default: from the file name)")
        p.set_defaults(func=cmd_import)

    if p := add("export", help="write one case of a study as another tool's input file"):
        p.add_argument("format", choices=["moordyn"], help="moordyn: a MoorDyn v2 input file")
        p.add_argument("config")
        p.add_argument(
            "--case",
            action="append",
            default=None,
            metavar="DIM=VALUE",
            help="the case's sweep coordinate, one per swept dimension",
        )
        p.add_argument("--out", default=None, help="output file (default: standard output)")
        p.set_defaults(func=cmd_export)

    if p := add("plot", help="quick-look plot of variables of a result file"):
        p.add_argument("result", help="a result file (.nc)")
        p.add_argument(
            "var", nargs="+", help="the variable(s) to draw on one axes (of one unit, e.g. N)"
        )
        p.add_argument(
            "--units",
            default=None,
            metavar="UNIT",
            help="unit of the values drawn (N kN MN, N/m kN/m MN/m, m mm km, s min h, Hz rad/s, "
            "rad deg; default: the file's SI unit)",
        )
        p.add_argument("--x", default=None, help="dimension on the x axis")
        p.add_argument("--hue", default=None, help="dimension drawn as one curve per value")
        p.add_argument(
            "--sel",
            action="append",
            default=None,
            metavar="DIM=VALUE",
            help="pick one value of a dimension: the nearest number, a label, or a swept "
            "vector as [0,0,1] (repeatable)",
        )
        p.add_argument("--out", default=None, help="PNG file (default: RESULT-VAR[-VAR...].png)")
        p.add_argument(
            "--shape",
            action="store_true",
            help="draw profiles on s as line shapes in the x-z plane",
        )
        p.set_defaults(func=cmd_plot)
    _add_lookup_parser(add)

    if p := add(
        "line-types",
        help="list the line-type library (line.segments.N.line_type): materials, formulas, "
        "coefficients and their sources",
    ):
        p.add_argument(
            "--diameter",
            type=float,
            default=None,
            metavar="D",
            help="also give every material's filled values at nominal diameter D [m]",
        )
        p.set_defaults(func=cmd_line_types)
    return parser if built else build_parser()


#: exit status after the reader of the output went away (as a shell reports SIGPIPE)
EXIT_BROKEN_PIPE = 141


def main(argv: list[str] | None = None) -> int:
    from .run.conventions import COMMAND

    words = sys.argv[1:] if argv is None else argv
    args, extra = build_parser(words[0] if words else None).parse_known_args(argv)
    if extra:  # refused as the whole parser words it (its usage names every command)
        build_parser().parse_args(argv)
    if argv is None:  # the program itself (not a caller in its own process)
        _skip_final_collection()
        if args.func is cmd_run:
            _pause_collection()
    from .study.loader import StudyError  # pydantic and the models: after the pause

    COMMAND[:] = ["cablestudy", *(sys.argv[1:] if argv is None else argv)]
    workers = getattr(args, "workers", None)
    if workers is not None and workers < 1:
        print(f"--workers {workers}: must be at least 1", file=sys.stderr)
        return 2
    try:
        code = args.func(args)
        sys.stdout.flush()  # inside the try: a closed pipe surfaces here, not at exit
        return code
    except StudyError as exc:
        print(f"invalid study:\n{exc}", file=sys.stderr)
        return 2
    except BrokenPipeError:
        # the reader stopped early (cablestudy schema | head): nothing more to say; stdout
        # goes to /dev/null so that the interpreter's final flush raises nothing either
        import os

        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return EXIT_BROKEN_PIPE
    finally:
        COMMAND.clear()  # a later library call in this process is not this command


#: whether this process paused the garbage collector for its start-up (:func:`main`)
_PAUSED: list[bool] = [False]


def _pause_collection() -> None:
    """Stop the garbage collector for the start-up of ``cablestudy run``: importing numba,
    scipy and the solvers, validating the study and loading the kernels allocate some
    150,000 long-lived objects, and the collections they trigger (about 300) only walk
    them again, about 0.1 s of a warm run's fixed cost. :func:`_resume_collection`
    starts it again before the study."""
    import gc

    if gc.isenabled():
        gc.disable()
        _PAUSED[0] = True


def _resume_collection() -> None:
    """Start the garbage collector paused by :func:`_pause_collection`, the start-up's
    objects frozen (kept out of the collections the study's own garbage triggers)."""
    import gc

    if _PAUSED[0]:
        _PAUSED[0] = False
        gc.freeze()
        gc.enable()


def _skip_final_collection() -> None:
    """Let the interpreter exit without the garbage collector walking the whole heap.

    After a run, the heap holds some 150,000 objects (numba's type system and loaded
    kernels, pydantic models, the solvers); the collections the interpreter makes while
    shutting down walk all of them, about 0.3 s of a warm run's fixed cost. Frozen by an
    atexit handler (the command has returned and closed its files by then), they are
    left to the operating system as the process ends; no handler or file depends on a
    cycle being collected at exit."""
    import atexit
    import gc

    atexit.register(gc.freeze)


def _add_lookup_parser(add: Callable[..., argparse.ArgumentParser | None]) -> None:
    p = add(
        "lookup",
        help="interpolate a quasi-static database (analysis.database) at an end-B position",
    )
    if p is None:
        return
    p.add_argument(
        "database",
        help="the database's own file (<name>.database.nc) or the study's result (<name>.nc)",
    )
    p.add_argument(
        "--at",
        nargs=2,
        type=float,
        required=True,
        metavar=("X", "Z"),
        help="horizontal distance [m] and height difference [m] of end B from end A (for a "
        "radial grid too: converted to its distance and angle)",
    )
    p.add_argument(
        "--sel",
        action="append",
        default=None,
        metavar="DIM=VALUE",
        help="one case of a swept study, by dimension and value (repeatable)",
    )
    p.add_argument(
        "--allow-flagged",
        action="store_true",
        help="interpolate in a cell the build flagged (cell_check: the patches cannot follow "
        "the table there, e.g. across the taut chord) instead of refusing; the result then "
        "carries a 'warning' naming the cell",
    )
    p.set_defaults(func=cmd_lookup)


def cmd_lookup(args: argparse.Namespace) -> int:
    """Print the interpolated end forces [N], tensions [N] and laid length [m] as JSON."""
    from .analyses.database import open_database

    sel: dict[str, object] = {}
    for item in args.sel or []:
        dim, _, value = item.partition("=")
        try:
            sel[dim] = float(value)
        except ValueError:
            sel[dim] = value
    try:
        db = open_database(args.database, **sel)
        db.allow_flagged = args.allow_flagged
        out = db.lookup(args.at[0], args.at[1])
        flagged = db.flagged_cell(*db.to_grid(args.at[0], args.at[1]))
        if flagged:  # only with --allow-flagged (refused otherwise)
            out["warning"] = f"flagged cell, the value may be wrong by any amount: {flagged}"
            print(f"lookup: warning: {out['warning']}", file=sys.stderr)
    except (ValueError, KeyError, OSError) as exc:
        print(f"lookup: {exc}", file=sys.stderr)
        return 2
    print(json.dumps({k: (v.tolist() if hasattr(v, "tolist") else v) for k, v in out.items()}))
    return 0


if __name__ == "__main__":
    sys.exit(main())
