"""`quenchsim bearings mode2 specimen|rcf`: the mode II crack toolkit.

    quenchsim bearings mode2 specimen --crack-mm 6 --width-mm 20 --thickness-mm 5 \
        --shear-load-range-kN 20 --opening-moment-Nm 30 --json
    quenchsim bearings mode2 rcf --p-max-GPa 2.5 6 [--shape line|circle|ellipse --ellipticity 1.7] \
        [--threshold 3] [--friction 0.5] [--inclusion-sqrt-area-um 16 24] --json

specimen: Delta K_II and static K_I from the paper's printed fits (sqrt(a) normalisation) and the test-condition
checks; rcf: critical diameter of a subsurface penny crack at depth b/2 under a rolling Hertz contact
(defaults: the paper's threshold 3 MPa sqrt(m) and face friction 0.5; nu of bearing steel); with
--inclusion-sqrt-area-um, each inclusion's sqrt(area) over the critical crack's (above 1: it grows).
"""

from __future__ import annotations

import argparse
from dataclasses import asdict

from quenchsim.bearings import mode2
from quenchsim.bearings.commands.ranges import Range
from quenchsim.bearings.kinematics import steel_properties
from quenchsim.errors import InputError

LENGTH_MM = Range(0.0, 1e4, low_open=True, unit="mm")
RANGES = {"crack_mm": LENGTH_MM, "width_mm": LENGTH_MM, "thickness_mm": LENGTH_MM,
          "shear_load_range_kN": Range(0.0, 1e5, unit="kN"), "opening_moment_Nm": Range(0.0, 1e6, unit="N m"),
          # the largest Hertz pressures of rolling contacts (static-capacity tests) stay below ~10 GPa
          "p_max_GPa": Range(0.0, 20.0, low_open=True, unit="GPa"),
          "ellipticity": Range(1.0, 20.0), "threshold": Range(0.0, 100.0, low_open=True, unit="MPa sqrt(m)"),
          "friction": Range(0.0, 2.0), "inclusion_sqrt_area_um": Range(0.0, 1e4, low_open=True, unit="um")}
"""Physical ranges of the numeric options (checked before any work, see :mod:`quenchsim.bearings.commands.ranges`)."""


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("task", choices=("specimen", "rcf"), help="specimen: test SIFs and checks; rcf: critical "
                        "subsurface crack size under rolling contact")
    parser.add_argument("--crack-mm", type=float, default=None, help="specimen: crack length a, mm")
    parser.add_argument("--width-mm", type=float, default=None, help="specimen: width W, mm")
    parser.add_argument("--thickness-mm", type=float, default=None, help="specimen: thickness t, mm")
    parser.add_argument("--shear-load-range-kN", type=float, default=None, help="specimen: range of the shear load P, kN")
    parser.add_argument("--opening-moment-Nm", type=float, default=0.0, help="specimen: static opening moment M, N m")
    parser.add_argument("--p-max-GPa", type=float, nargs="+", default=None, help="rcf: maximum contact pressure(s), GPa")
    parser.add_argument("--shape", choices=("line", "circle", "ellipse"), default="line",
                        help="rcf: contact shape (ellipse: with --ellipticity, transverse / rolling semi-axis)")
    parser.add_argument("--ellipticity", type=float, default=None, help="rcf: ellipse semi-axis ratio k in [1, 20]")
    parser.add_argument("--threshold", type=float, default=None, help="rcf: Delta K_IIth, MPa sqrt(m) (default 3)")
    parser.add_argument("--friction", type=float, default=None, help="rcf: crack-face friction (default 0.5)")
    parser.add_argument("--inclusion-sqrt-area-um", type=float, nargs="+", default=None,
                        help="rcf: inclusion sizes (Murakami's sqrt(area), um) compared with the critical crack")


def _need(args: argparse.Namespace, *names: str) -> None:
    for name in names:
        if getattr(args, name) is None:
            raise InputError("--" + name.replace("_", "-"), None, f"required for mode2 {args.task}")


def run(args: argparse.Namespace) -> dict:
    if args.task == "specimen":
        _need(args, "crack_mm", "width_mm", "thickness_mm", "shear_load_range_kN")
        if args.crack_mm >= args.width_mm:
            raise InputError("--crack-mm", args.crack_mm, f"must be below --width-mm = {args.width_mm} mm")
        s = mode2.specimen_state(args.crack_mm * 1e-3, args.width_mm * 1e-3, args.thickness_mm * 1e-3,
                                 args.shear_load_range_kN * 1e3, args.opening_moment_Nm)
        out = asdict(s)
        for key in ("delta_K_II", "K_I_static", "K_I_parasitic"):
            out[f"{key}_MPa_sqrt_m"] = out.pop(key) / 1e6
        out["notes"] = list(s.notes)
        out["F_II"], out["F_I"] = float(mode2.F_II(s.a_over_W)), float(mode2.F_I(s.a_over_W))
        return out
    _need(args, "p_max_GPa")
    if args.shape == "ellipse" and args.ellipticity is None:
        raise InputError("--ellipticity", None, "required with --shape ellipse (a value in [1, 20])")
    shape = "line" if args.shape == "line" else "ellipse"
    k = 1.0 if args.shape == "circle" else (args.ellipticity or 1.0)
    nu = steel_properties()["poisson"]
    rows = []
    for p in args.p_max_GPa:
        c = mode2.critical_crack(p * 1e9, shape, k, nu=nu,
                                 threshold_Pa_sqrt_m=None if args.threshold is None else args.threshold * 1e6,
                                 friction=args.friction)
        row = {"p_max_GPa": p, "critical_diameter_um": c.critical_diameter_m * 1e6,
               "shear_range_MPa": c.shear_range_Pa / 1e6, "shear_range_factor": c.shear_range_factor}
        if args.inclusion_sqrt_area_um:
            row["inclusion_over_critical"] = [mode2.inclusion_over_critical(size * 1e-6, c.critical_diameter_m)
                                              for size in args.inclusion_sqrt_area_um]
        rows.append(row)
    d = mode2.crack_data()
    return {"shape": args.shape, "ellipticity": None if args.shape == "line" else k, "nu": nu,
            "threshold_MPa_sqrt_m": args.threshold or d["material"]["delta_K_IIth_MPa_sqrt_m"],
            "friction": d["rolling_contact"]["face_friction"] if args.friction is None else args.friction,
            "depth_over_b": d["rolling_contact"]["depth_over_b"], "cracks": rows}
