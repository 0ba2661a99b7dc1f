"""`quenchsim bath CASE.toml --condition N [--png out.png] [--spacing-mm 2]`: what the bath model assumes.

Prints, per boundary segment of the case's section, the local oil speed (jets + rotation), the
Leidenfrost temperature and the segment-mean HTC at a set of surface temperatures; with ``--png``
also plots HTC(T) per segment and the local speed along the section outline.
"""

from __future__ import annotations

import argparse
from pathlib import Path

from quenchsim.errors import InputError


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("case", type=Path, help="case file (TOML) with a [quench.bath] table, or the name of a shipped case")
    parser.add_argument("--condition", help="named condition of the case file")
    parser.add_argument("--png", type=Path, help="write HTC(T) per segment to this PNG (and the speeds to *_speed.png)")
    parser.add_argument("--spacing-mm", type=float, default=2.0, help="spacing of the boundary points (mm)")


def run(args: argparse.Namespace) -> int:
    from quenchsim.bath.plots import plot_htc, plot_velocity
    from quenchsim.bath.segments import TABLE_T_C, outline_htc, segment_table
    from quenchsim.case import load_case
    from quenchsim.shipped import resolve_case

    if not args.spacing_mm > 0:
        raise InputError("--spacing-mm", args.spacing_mm, "must be > 0")
    case = load_case(resolve_case(args.case), args.condition)
    if case.bath is None:
        raise InputError("quench.htc_model", case.quench.htc_model, "must be 'bath' for `quenchsim bath`")
    points, htc = outline_htc(case.profile, case.bath, args.spacing_mm * 1e-3)
    bath = case.get("quench.bath", {})
    print(f"{case.name} condition {case.condition or '-'}: {bath.get('quenchant')} at {bath.get('oil_temperature_C')} C, "
          f"ID jets {bath.get('id_jet_speed_mm_s', '-')} mm/s, OD jets {bath.get('od_jet_speed_mm_s', '-')} mm/s, "
          f"{bath.get('rotation_rpm', 0)} rpm, agitation {case.bath.agitation} "
          f"({case.bath.agitation_m_s:g} m/s bulk), support {case.bath.support}")
    header = f"{'segment':<22}{'speed m/s':>12}{'T_L C':>10}" + "".join(f"{f'h@{T}':>8}" for T in TABLE_T_C)
    print(header)
    print("-" * len(header))
    for row in segment_table(htc):
        lo, hi = row["speed_m_s"]
        tl_lo, tl_hi = row["leidenfrost_C"]
        print(f"{row['segment']:<22}{f'{lo:.2f}-{hi:.2f}':>12}{f'{tl_lo:.0f}-{tl_hi:.0f}':>10}"
              + "".join(f"{row['h_mean_W_m2K'][T]:>8.0f}" for T in TABLE_T_C))
    print("h: segment-mean HTC in W/(m2 K) at the surface temperature (C) named in the column")
    if args.png:
        args.png.parent.mkdir(parents=True, exist_ok=True)
        plot_htc(htc, f"{case.name}, condition {case.condition or '-'}", args.png)
        speed = args.png.with_name(args.png.stem + "_speed.png")
        plot_velocity({case.condition or "-": (points, htc)}, f"{case.name}: local oil speed", speed)
        print(f"wrote {args.png} and {speed}")
    return 0
