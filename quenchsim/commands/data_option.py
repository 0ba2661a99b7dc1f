"""The ``--data DIR`` option of the commands that read steels and quenchants by name (quenchsim.materials: the
search path), shared by the command modules and applied once by :func:`quenchsim.cli.main`."""

from __future__ import annotations

import argparse

DATA_COMMANDS = ("run", "sweep", "calibrate", "optimise", "bath", "cct")
"""Commands given ``--data`` by the CLI itself; ``material fit`` and ``quenchant fit | from-datasheet | show`` add
it to their sub-commands (``ttt --data`` is the data file it overlays)."""


def add_data_option(parser: argparse.ArgumentParser) -> None:
    """``--data DIR`` (repeatable): a data folder laid out like materials/, searched before ./materials and the
    shipped data."""
    parser.add_argument("--data", dest="data_folders", action="append", default=[], metavar="DIR",
                        help="your data folder (NAME.toml steels, quenchants/NAME.toml oils), searched by name before "
                             "./materials and the shipped data; repeatable")
