"""Command line: ``cablestudy run | validate | schema | figures | bench``."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from .config.loader import StudyError


def _size(text: str) -> int:
    from .config.safe_yaml import parse_size

    try:
        return parse_size(text)
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def _load(path: str, max_bytes: int | None = None):  # noqa: ANN202
    from .analyses import check_supported
    from .cases import expand_cases
    from .config.loader import read_study_source

    src = read_study_source(path, max_bytes=max_bytes)
    axes, cases = expand_cases(src)
    check_supported(cases, src)
    return src, axes, cases


def cmd_validate(args: argparse.Namespace) -> int:
    src, axes, cases = _load(args.config, args.max_study_size)
    dims = ", ".join(f"{a.name}={a.size}" for a in axes) or "no sweep"
    print(f"{args.config}: valid study {src.data['name']!r}: {len(cases)} cases ({dims})")
    return 0


def cmd_run(args: argparse.Namespace) -> int:
    from .runner import AUTO, SCHEDULERS, SchedulerUnreachable, run_study

    scheduler = args.scheduler or AUTO
    if scheduler not in SCHEDULERS and "://" not in scheduler:
        print(
            f"--scheduler {scheduler!r}: allowed are {', '.join(SCHEDULERS)} or the address "
            "of a running dask.distributed scheduler (tcp://host:port)",
            file=sys.stderr,
        )
        return 2
    src, axes, cases = _load(args.config, args.max_study_size)
    from .analyses import warm_up

    warm_up(cases)
    try:
        summary = run_study(
            src,
            axes,
            cases,
            args.out,
            scheduler=scheduler,
            workers=args.workers,
            use_cache=not args.no_cache,
            progress=args.progress,
        )
    except KeyboardInterrupt:
        print(
            "\ninterrupted: finished cases are cached; run the same command again to resume",
            file=sys.stderr,
        )
        return 130
    except PermissionError as exc:
        print(f"cannot write the results: {exc}", file=sys.stderr)
        return 1
    except SchedulerUnreachable as exc:
        print(f"{exc}; finished cases are cached", file=sys.stderr)
        return 1
    print(summary.report())
    return 0


def cmd_schema(args: argparse.Namespace) -> int:
    from .config import Study

    schema = {
        "$schema": "https://json-schema.org/draft/2020-12/schema",
        "title": "cablestudy study file",
        **Study.model_json_schema(),
    }
    schema["title"] = "cablestudy study file"
    print(json.dumps(schema, indent=2))
    return 0


def cmd_figures(args: argparse.Namespace) -> int:
    from .figures import build_all

    written = build_all(
        Path(args.results), Path(args.out), configs=Path(args.configs), run_missing=not args.no_run
    )
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


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="cablestudy", description=__doc__)
    sub = parser.add_subparsers(dest="command", required=True)

    p = sub.add_parser("run", help="run a study file and write <out>/<name>.nc")
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
    p.add_argument("--no-cache", action="store_true", help="recompute every case")
    p.add_argument(
        "--progress",
        action=argparse.BooleanOptionalAction,
        default=None,
        help="progress bar (default: on a terminal)",
    )
    _add_size_option(p)
    p.set_defaults(func=cmd_run)

    p = sub.add_parser("validate", help="check a study file without running it")
    p.add_argument("config")
    _add_size_option(p)
    p.set_defaults(func=cmd_validate)

    p = sub.add_parser("schema", help="print the JSON Schema of study files")
    p.set_defaults(func=cmd_schema)

    p = sub.add_parser("figures", help="build the paper figures from results datasets")
    p.add_argument("--results", default="results")
    p.add_argument("--out", default="results/figures")
    p.add_argument("--configs", default="configs")
    p.add_argument("--no-run", action="store_true", help="do not run missing studies")
    p.set_defaults(func=cmd_figures)

    p = sub.add_parser("bench", help="run time against error benchmarks")
    p.add_argument("--out", default="results/bench")
    p.add_argument("--quick", action="store_true", help="fewer repeats and settings")
    p.add_argument("--only", default=None, help="comma-separated benchmark modules (wp_*)")
    p.add_argument("--readme", default=None, help="README to update between bench markers")
    p.add_argument("--docs", default=None, help="folder for the committed plots")
    p.set_defaults(func=cmd_bench)
    return parser


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    workers = getattr(args, "workers", None)
    if workers is not None and workers < 1:
        print(f"--workers {workers}: must be at least 1", file=sys.stderr)
        return 2
    try:
        return args.func(args)
    except StudyError as exc:
        print(f"invalid study:\n{exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
