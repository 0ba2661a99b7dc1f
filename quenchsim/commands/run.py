"""`quenchsim run CASE.toml|NAME --condition NAME --out DIR [--mesh-size MM] [--set KEY=VALUE ...] [--resume] [--force]
[--uncertainty N [--posterior DIR]]`."""

from __future__ import annotations

import argparse
import json
import logging
from pathlib import Path

from quenchsim.case import load_case
from quenchsim.commands.mesh_limit import MAX_TRIANGLES, refuse_large_mesh
from quenchsim.errors import InputError
from quenchsim.inputs.reader import parse_value
from quenchsim.report.lengths import LENGTH_DECIMALS, mm
from quenchsim.results import files
from quenchsim.shipped import resolve_case


def parse_sets(items: list[str]) -> dict[str, object]:
    """``["quench.time_s=600", "geometry.type=\\"profile\\""]`` -> dotted overrides (values parsed as TOML)."""
    out: dict[str, object] = {}
    for item in items or []:
        key, sep, raw = item.partition("=")
        if not sep or not key:
            raise InputError("--set", item, "must look like KEY=VALUE, e.g. quench.time_s=600")
        out[key.strip()] = parse_value(raw)
    return out


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("case", type=Path, help="case file (TOML), or the name of a shipped case (quenchsim cases)")
    parser.add_argument("--condition", help="named condition of the case file")
    parser.add_argument("--out", type=Path, help="output directory (default runs/<case>_<condition>)")
    parser.add_argument("--mesh-size", type=float, help="core element size in mm (surface size scales with it)")
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                        help="override any case field, e.g. --set quench.time_s=600")
    parser.add_argument("--resume", action="store_true",
                        help="continue the interrupted run of this case in --out from its checkpoint")
    parser.add_argument("--force", action="store_true",
                        help="write into --out even when it is a non-empty folder that is not a quenchsim run (a "
                             "run folder's earlier outputs are always replaced), and mesh above "
                             f"{MAX_TRIANGLES:,} estimated triangles")
    parser.add_argument("--quiet", action="store_true", help="no progress bar")
    parser.add_argument("--json", action="store_true", help="print the key results as JSON instead of a table")
    parser.add_argument("--uncertainty", type=int, metavar="N",
                        help="then N runs drawn from --posterior (or the data files' priors): median and 5-95 %% band of "
                             "every summary quantity (summary.json 'uncertainty', the report)")
    parser.add_argument("--posterior", type=Path, metavar="DIR", help="a `quenchsim calibrate` output folder")
    parser.add_argument("--workers", type=int, default=2, help="Dask workers for --uncertainty (0: this process)")


def run(args: argparse.Namespace) -> int:
    from quenchsim.pipeline import run as run_case

    overrides = parse_sets(args.set)
    case = load_case(resolve_case(args.case), args.condition, overrides)
    if args.mesh_size is not None:
        if args.mesh_size <= 0:
            raise InputError("--mesh-size", args.mesh_size, "must be > 0 (mm)")
        case = case.with_mesh_size(args.mesh_size)
    refuse_large_mesh(case, args.force)
    out = args.out or Path("runs") / f"{case.name}_{case.condition or 'base'}"
    if args.uncertainty is not None:   # checked before the run starts
        from quenchsim.calibration.propagate import uncertain_inputs

        uncertain_inputs(case, args.uncertainty, args.posterior)
    logging.basicConfig(level=logging.WARNING, format="quenchsim: %(message)s")
    result = run_case(case, out, progress=not args.quiet, resume=args.resume, force=args.force)
    s = result.summary
    if args.uncertainty is not None:
        from quenchsim.calibration.propagate import band_table, propagate

        s["uncertainty"] = propagate(case, out, args.uncertainty, posterior=args.posterior, workers=args.workers,
                                     progress=not args.quiet)
        if not args.json:
            print(band_table(s["uncertainty"]))
    if args.json:
        # a material that does not transform has no hardness (summary.json "notes" says so)
        print(json.dumps({"out": str(out), "status": s["status"], "probes": s["probes"],
                          **{k: s[k] for k in ("hardness", "notes", "dimensions_mm") if k in s},
                          "end_state": s["end_state"], "solver": s["solver"],
                          **({"uncertainty": s["uncertainty"]} if "uncertainty" in s else {})}, indent=2))
    else:
        print(summary_table(s, out))
    return 0


def summary_table(s: dict, out: Path) -> str:
    """A short plain-text table of a run's key results (everything else is in summary.json)."""
    rows = [f"{s['case']} condition {s['condition'] or '-'}: status {files.run_status(s)}, "
            f"{s['solver']['steps']} steps, {s['solver']['wall_time_s']:.1f} s wall -> {out}"]
    warning = files.status_warning(s)
    if warning:
        rows.append(f"WARNING: {warning}")
    rows.append(f"{'probe':<10}{'t to 500 C (s)':>16}{'t to 300 C (s)':>16}{'t8/5 (s)':>10}")
    fmt = lambda v, w: f"{v:>{w}.1f}" if v is not None else f"{'-':>{w}}"  # noqa: E731
    for name, p in s["probes"].items():
        rows.append(f"{name:<10}{fmt(p['t_to_500C_s'], 16)}{fmt(p['t_to_300C_s'], 16)}{fmt(p['t8_5_s'], 10)}")
    if "hardness" in s:
        h = s["hardness"]
        # a solid section's "bore" depth is None: its traverse starts on the axis, not on a surface
        if h.get("through_hardened_mid"):   # the depths are the whole wall: say so, not a number equal to it
            rows.append(f"HRC58 depth at mid-width: through-hardened (>= {h.get('threshold_HRC', 58.0):g} HRC across "
                        f"the wall); core {h['core_HRC']:.1f} HRC")
        else:
            rows.append("HRC58 depth at mid-width (mm): "
                        + ", ".join(f"{k.split('_')[1]} {mm(v)}" for k, v in h["depth_mm"].items())
                        + f"; core {h['core_HRC']:.1f} HRC")
    rows += [f"note: {note}" for note in s.get("notes", [])]
    if "dimensions_mm" not in s:   # never a silence that reads as "unchanged"
        rows.append("note: no mechanics in this run: no dimensions, shape, distortion or residual stresses computed")
    if "dimensions_mm" in s:
        d = s["dimensions_mm"]
        m = s.get("measured", {}).get("change", {})
        rows.append(f"{'dimension (mm)':<16}{'before':>10}{'after':>10}{'change':>10}"
                    + (f"{'measured':>10}{'sim - meas':>12}" if m else ""))
        for k in d["change"]:
            rows.append(f"{k:<16}{mm(d['before'][k]):>10}{mm(d['after'][k]):>10}{d['change'][k]:>+10.{LENGTH_DECIMALS}f}"
                        + (f"{m[k]['measured']:>+10.{LENGTH_DECIMALS}f}"
                           f"{m[k]['simulated_minus_measured']:>+12.{LENGTH_DECIMALS}f}" if k in m else ""))
        if m:
            rows.append(f"measured: {s['measured']['source']}")
    if "shape_mm" in s:
        rows += shape_rows(s["shape_mm"])
    if "tempered" in s:
        rows += tempered_rows(s)
    return "\n".join(rows)


def tempered_rows(s: dict) -> list[str]:
    """The as-quenched and the tempered state side by side (a run with a [temper]): hardness, retained austenite,
    dimensions, shape and residual hoop stress."""
    t = s["tempered"]
    temper = t["temper"]
    rows = [f"temper {temper['temperature_C']:g} C, {temper['time_s'] / 3600.0:g} h in the furnace",
            f"{'as quenched -> tempered':<34}{'quenched':>10}{'tempered':>10}{'change':>10}"]

    def row(label: str, a: float | None, b: float | None, fmt: str = ".3f") -> None:
        if a is not None and b is not None:
            rows.append(f"{label:<34}{a:>10{fmt}}{b:>10{fmt}}{b - a:>+10{fmt}}")

    if "hardness" in t:
        row("core HRC", s["hardness"]["core_HRC"], t["hardness"]["core_HRC"], ".1f")
        for where in ("od_mid", "bore_mid"):
            row(f"surface HRC {where}", s["hardness"]["surface_HRC"].get(where),
                t["hardness"]["surface_HRC"].get(where), ".1f")
        row("retained austenite (mean)", s["phases_final"]["austenite"]["mean"],
            t["phases_final"]["austenite"]["mean"], ".4f")
    if "dimensions_mm" in t:
        for k in t["dimensions_mm"]["after"]:
            row(f"{k} (mm)", s["dimensions_mm"]["after"][k], t["dimensions_mm"]["after"][k], ".3f")
        for key, label in SHAPE_ROWS:
            row(f"{label} (mm)", s["shape_mm"]["after"][key], t["shape_mm"]["after"][key], ".4f")
        for where, value in t["residual_stress_MPa"]["hoop"].items():
            row(f"hoop stress {where} (MPa)", s["residual_stress_MPa"]["hoop"][where], value, ".0f")
    return rows


SHAPE_ROWS = (("bore_taper", "bore taper"), ("od_taper", "OD taper"), ("bore_crown", "bore crown"),
              ("od_crown", "OD crown"), ("top_face_dish", "top face dish"), ("bottom_face_dish", "bottom dish"))


def shape_rows(shape: dict) -> list[str]:
    """The inspector's shape measures (summary.json ``shape_mm``) as table rows: before, after, change (mm)."""
    g = shape["gauge"]["heights_before_mm"]
    rows = [f"{'shape (mm)':<16}{'before':>10}{'after':>10}{'change':>10}   gauge heights "
            f"{mm(g['bottom'])} / {mm(g['mid'])} / {mm(g['top'])} mm, taper top - bottom, crown mid - ends"]
    for key, label in SHAPE_ROWS:
        b, a, c = (shape[part][key] for part in ("before", "after", "change"))
        if c is not None:
            rows.append(f"{label:<16}{mm(b):>10}{mm(a):>10}{c:>+10.{LENGTH_DECIMALS}f}")
    return rows
