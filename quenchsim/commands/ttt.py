"""`quenchsim ttt MATERIAL [--T-aust C] [--temperatures ...] [--data DATA.toml] [--png out.png] [--json]`: TTT diagram.

Prints the isothermal 1 % and 99 % times of each diffusional reaction the material's kinetics imply, and Ms;
``--png`` draws the diagram with the TTT points of the data the material was fitted to (its [kinetics.fit]
record) or of ``--data``.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np

from quenchsim.commands.material import data_file_path
from quenchsim.fitting.diagram_data import DiagramData, load_diagram_data
from quenchsim.fitting.plots import plot_ttt, ttt_lines
from quenchsim.materials import load_material, materials_dir
from quenchsim.metallurgy import load_kinetics


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("material", help="material name (materials/NAME.toml) or path to a .toml file")
    parser.add_argument("--T-aust", dest="T_aust", type=float, default=845.0, help="austenitising temperature in C (default 845)")
    parser.add_argument("--temperatures", type=float, nargs="+", metavar="C", help="temperatures of the table (default: 250-700 C)")
    parser.add_argument("--data", help="data file to overlay, or its name in a data folder's data/ (default: the one the "
                                         "material was fitted to)")
    parser.add_argument("--png", type=Path, help="write the diagram to this PNG file")
    parser.add_argument("--json", action="store_true", help="print one JSON object instead of the table")


def fitted_data(material: dict, explicit: str | Path | None) -> DiagramData | None:
    """The data file given (a path or a name, :func:`quenchsim.commands.material.data_file_path`), or the one recorded
    in the material's [kinetics.fit] (None if neither)."""
    if explicit is not None:
        return load_diagram_data(data_file_path(str(explicit)))
    record = material.get("kinetics", {}).get("fit")
    if not record:
        return None
    path = Path(record["data_file"])
    return load_diagram_data(path if path.is_absolute() or path.exists() else materials_dir().parent / path)


def run(args: argparse.Namespace) -> int:
    material = load_material(args.material)
    kin = load_kinetics(material, args.T_aust)
    T = np.asarray(args.temperatures if args.temperatures else np.arange(250.0, 701.0, 25.0), dtype=float)
    lines = ttt_lines(kin, T)
    if args.png:
        plot_ttt(kin, fitted_data(material, args.data), args.png)
    if args.json:
        clean = lambda a: [float(x) if np.isfinite(x) else None for x in a]  # noqa: E731
        print(json.dumps({"material": kin.material, "T_aust_C": kin.T_aust_C, "Ms_C": kin.Ms_C, "T_C": T.tolist(),
                          **{f"{p}_{w}_s": clean(v) for p, (s, f) in lines.items() for w, v in (("start", s), ("finish", f))}}))
        return 0
    print(f"{kin.material} austenitised at {kin.T_aust_C:g} C: Ms {kin.Ms_C:.0f} C; isothermal 1 % / 99 % times (s)")
    print(f"{'T C':>6} " + " ".join(f"{p + ' 1%':>12} {p + ' 99%':>12}" for p in lines))
    fmt = lambda x: f"{x:12.4g}" if np.isfinite(x) else f"{'-':>12}"  # noqa: E731
    for i, t in enumerate(T):
        print(f"{t:6.0f} " + " ".join(f"{fmt(s[i])} {fmt(f[i])}" for s, f in lines.values()))
    if args.png:
        print(f"wrote {args.png}")
    return 0
