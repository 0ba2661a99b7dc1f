"""The `quenchsim` command line: one subcommand per task (``quenchsim --help`` lists them all, from ``COMMANDS``).

Commands are registered in ``COMMANDS`` (name -> module with ``configure(parser)`` and
``run(args) -> int``); each module is imported only when its command is used, so a slow
import (pyvista, dask) never delays another command.
"""

from __future__ import annotations

import argparse
import importlib
import importlib.util
import json
import os
import sys

from quenchsim.commands.data_option import DATA_COMMANDS, add_data_option
from quenchsim.errors import QuenchsimError, RunInterrupted

COMMANDS: dict[str, tuple[str, str]] = {
    "run": ("quenchsim.commands.run", "run one case and condition, write VTK/probes/summary"),
    "cases": ("quenchsim.commands.cases", "list the shipped cases, or copy one into your folder"),
    "mesh": ("quenchsim.commands.mesh", "build and write the section mesh of a case"),
    "cct": ("quenchsim.commands.cct", "plot the CCT diagram implied by a material's kinetics"),
    "ttt": ("quenchsim.commands.ttt", "print/plot the TTT diagram of a material's kinetics, with its fitted data"),
    "material": ("quenchsim.commands.material", "material fit: steel kinetics from CCT / TTT / Jominy data"),
    "bath": ("quenchsim.commands.bath", "show the bath model: local velocities and HTC(T) per segment"),
    "sweep": ("quenchsim.commands.sweep", "run a parameter sweep on Dask distributed"),
    "optimise": ("quenchsim.commands.optimise", "process design: the settings that meet constraints and minimise distortion"),
    "calibrate": ("quenchsim.commands.calibrate", "fit uncertain inputs to measurements: screening, surrogate, posterior"),
    "report": ("quenchsim.commands.report", "HTML/Markdown report of run or sweep directories"),
    "validate": ("quenchsim.commands.validate", "run the studies of validation/, write reports/, exit 1 on a missed target"),
    "stability": ("quenchsim.commands.stability", "size change of a tempered part held at a service temperature"),
    "view": ("quenchsim.commands.view", "off-screen render of a run's final field to PNG"),
    "quenchant": ("quenchsim.commands.quenchant", "still-bath h(T_s) of a quenchant from its ISO 9950 probe curve"),
}


def _available(module: str) -> bool:
    try:
        return importlib.util.find_spec(module) is not None
    except ModuleNotFoundError:
        return False


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="quenchsim", description="The quenchsim command line: "
                                     f"{' | '.join([*COMMANDS, 'bearings'])} (quenchsim COMMAND --help for each).")
    sub = parser.add_subparsers(dest="command", required=True)
    argv = sys.argv[1:]
    for name, (module, help_text) in COMMANDS.items():
        if not _available(module):
            continue
        p = sub.add_parser(name, help=help_text)
        # import only the command being run (keeps `quenchsim --help` and other verbs fast)
        if name in argv[:1]:
            importlib.import_module(module).configure(p)
            if name in DATA_COMMANDS:
                add_data_option(p)
        p.set_defaults(_module=module)

    from quenchsim.bearings.commands import VERBS

    bearings = sub.add_parser("bearings", help="bearing-analysis solvers (one JSON object with --json)")
    bsub = bearings.add_subparsers(dest="verb", required=True)
    for verb, module in VERBS.items():
        if not _available(module):
            continue
        p = bsub.add_parser(verb)
        if argv[:2] == ["bearings", verb]:
            importlib.import_module(module).configure(p)
        p.add_argument("--json", action="store_true", help="print one JSON object on stdout")
        p.set_defaults(_bearing_module=module)
    return parser


SINGLE_THREAD_BLAS = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")
"""The solvers work on arrays of ~1e3-1e5 values where a threaded BLAS costs more in thread start-up than it
gains (measured: a 14k dot product 2.2 ms threaded vs 3.4 us single-threaded on 2 loaded cores). The command
line sets these to 1 for its own process unless the user set them; a library user decides for themselves."""


def main(argv: list[str] | None = None) -> int:
    """Run one command (``argv``, default the process's arguments); the exit status: 0, 1 (a study or sweep missed or
    failed), 2 (bad input, one line on stderr), 130 (interrupted), 141 (the reader of stdout went away)."""
    try:
        try:
            return _command(argv)
        finally:
            sys.stdout.flush()   # here, where a closed pipe can still be caught
    except BrokenPipeError:
        # the reader stopped reading (`quenchsim ... | head`): stop quietly, as a command killed by SIGPIPE; stdout
        # goes to /dev/null so that the interpreter's flush at exit does not raise again
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 141


def _command(argv: list[str] | None) -> int:
    for var in SINGLE_THREAD_BLAS:
        os.environ.setdefault(var, "1")
    if argv is not None:
        sys.argv = [sys.argv[0], *argv]
    parser = build_parser()
    args = parser.parse_args()
    try:
        if getattr(args, "data_folders", None):
            from quenchsim.materials import use_data_folders

            use_data_folders(args.data_folders)
        if getattr(args, "_bearing_module", None):
            from quenchsim.bearings.commands.ranges import check_ranges

            verb = importlib.import_module(args._bearing_module)
            check_ranges(args, getattr(verb, "RANGES", {}))
            result = verb.run(args)
            if args.json:
                print(json.dumps(result, default=float))
            else:
                from quenchsim.commands.plain_text import plain_lines

                print("\n".join(plain_lines(result)))
            return 0
        return int(importlib.import_module(args._module).run(args) or 0)
    except (RunInterrupted, KeyboardInterrupt) as exc:
        print(f"quenchsim: {exc or 'interrupted'}", file=sys.stderr)
        return 130
    except QuenchsimError as exc:
        print(f"quenchsim: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
