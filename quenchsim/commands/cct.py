"""`quenchsim cct MATERIAL [--T-aust C] [--rates ...] [--png out.png] [--json]`: the CCT diagram a material's kinetics imply.

Prints, for each linear cooling rate from T_aust to 20 C, the start/finish temperatures of pearlite and
bainite, the final phase fractions and the as-quenched hardness, so the model can be held against a
catalogue CCT diagram; ``--png`` also draws it.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np

from quenchsim.errors import InputError
from quenchsim.materials import load_material
from quenchsim.metallurgy import load_kinetics
from quenchsim.metallurgy.cct import cct_diagram

DEFAULT_RATES_C_S = (0.1, 0.3, 1.0, 3.0, 10.0, 30.0, 100.0, 300.0)


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("material", help="material name (materials/NAME.toml) or path to a .toml file")
    parser.add_argument("--T-aust", dest="T_aust", type=float, default=845.0,
                        help="austenitising temperature in C (default 845)")
    parser.add_argument("--rates", type=float, nargs="+", default=list(DEFAULT_RATES_C_S), metavar="C_PER_S",
                        help="linear cooling rates in C/s (default: 0.1 ... 300)")
    parser.add_argument("--png", type=Path, help="write the diagram to this PNG file")
    parser.add_argument("--overlay", action="store_true",
                        help="with --png: overlay the CCT data the material was fitted to (its [kinetics.fit] data file)")
    parser.add_argument("--json", action="store_true", help="print one JSON object instead of the table")


def _json_list(values: np.ndarray) -> list[float | None]:
    """Plain JSON: NaN (no such line) becomes null."""
    return [float(v) if np.isfinite(v) else None for v in np.asarray(values, dtype=float)]


def _fmt(x: float) -> str:
    return "-" if not np.isfinite(x) else f"{x:.0f}"


def run(args: argparse.Namespace) -> int:
    rates = np.sort(np.asarray(args.rates, dtype=float))
    if np.any(~np.isfinite(rates)) or np.any(rates <= 0):
        raise InputError("--rates", list(args.rates), "cooling rates must be positive numbers (C/s)")
    material = load_material(args.material)
    kin = load_kinetics(material, args.T_aust)
    d = cct_diagram(kin, rates, args.T_aust)
    if args.png and args.overlay:
        from quenchsim.commands.ttt import fitted_data
        from quenchsim.fitting.plots import plot_cct_overlay

        plot_cct_overlay(kin, fitted_data(material, None), args.png)
    elif args.png:
        from quenchsim.metallurgy.plots import plot_cct

        args.png.parent.mkdir(parents=True, exist_ok=True)
        plot_cct(cct_diagram(kin, np.logspace(-1, 3, 33), args.T_aust), kin, args.png)
    if args.json:
        out = {"material": d.material, "T_aust_C": d.T_aust_C, "Ms_C": d.Ms_C, "dissolved_wt": dict(kin.dissolved),
               "rates_C_s": rates.tolist(),
               "start_T_C": {p: _json_list(v) for p, v in d.start_T_C.items()},
               "finish_T_C": {p: _json_list(v) for p, v in d.finish_T_C.items()},
               "final_fractions": {p: _json_list(v) for p, v in d.final_fractions.items()},
               "hardness_HV": _json_list(d.hardness_HV), "hardness_HRC": _json_list(d.hardness_HRC)}
        print(json.dumps(out, allow_nan=False))
        return 0
    print(f"{d.material} austenitised at {d.T_aust_C:g} C: dissolved C {kin.dissolved['C']:.3f} %, "
          f"Ms {d.Ms_C:.0f} C; linear cooling to {d.T_end_C:g} C")
    upper = ", ".join(f"{p} below {r.T_upper_C:.0f} C ({r.model})" for p, r in kin.reactions.items())
    print(f"reactions: {upper}")
    print(f"{'rate C/s':>9} {'P start':>8} {'P end':>6} {'B start':>8} {'B end':>6} "
          f"{'pearl.':>7} {'bain.':>7} {'mart.':>7} {'ret.A':>7} {'HV':>5} {'HRC':>5}")
    for i, rate in enumerate(d.rates_C_s):
        cells = []
        for p in ("pearlite", "bainite"):
            cells += [_fmt(d.start_T_C[p][i]) if p in d.start_T_C else "-",
                      _fmt(d.finish_T_C[p][i]) if p in d.finish_T_C else "-"]
        f = d.final_fractions
        hrc = d.hardness_HRC[i]
        print(f"{rate:9.3g} {cells[0]:>8} {cells[1]:>6} {cells[2]:>8} {cells[3]:>6} {f['pearlite'][i]:7.3f} "
              f"{f['bainite'][i]:7.3f} {f['martensite'][i]:7.3f} {f['austenite'][i]:7.3f} {d.hardness_HV[i]:5.0f} "
              f"{('-' if not np.isfinite(hrc) else f'{hrc:.1f}'):>5}")
    if args.png:
        print(f"wrote {args.png}")
    return 0
