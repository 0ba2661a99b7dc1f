"""`quenchsim bearings encoder field|remanence|pulses`: multipole magnetic encoder of a sensor bearing.

    quenchsim bearings encoder field --pole-width-mm 1.5 --thickness-mm 1 --remanence-T 0.22 \
        --gap-mm 0 0.5 1 2 3 [--recoil-permeability 1] [--backing air|iron] [--operate-mT 3] --json
    quenchsim bearings encoder remanence --pole-width-mm 1.5 --thickness-mm 1 --gap-mm 1 --field-mT 15 --json
    quenchsim bearings encoder pulses --poles 64 --magnet-diameter-mm 30.55 --thickness-mm 1 --remanence-T 0.22 \
        --gap-mm 1 --operate-mT 3 --release-mT -3 [--eccentricity-mm 0.05] [--b-offset-deg 90] --json

The pole width may be given directly or as --poles with --magnet-diameter-mm (p = pi D / poles). Fields are the
pole-centre normal component B_y (closed form; linear magnet, no iron apart from an ideal back plate).
"""

from __future__ import annotations

import argparse
import math

from quenchsim.bearings import encoder as enc
from quenchsim.bearings.commands.ranges import DIAMETER_MM, Range
from quenchsim.errors import InputError

LENGTH_MM = Range(0.0, 1e3, low_open=True, unit="mm")
FIELD_MT = Range(-2000.0, 2000.0, unit="mT")
RANGES = {"pole_width_mm": LENGTH_MM, "thickness_mm": LENGTH_MM, "magnet_diameter_mm": DIAMETER_MM,
          "poles": Range(2, 100000, integer=True), "remanence_T": Range(0.0, 2.0, low_open=True, unit="T"),
          "recoil_permeability": Range(1.0, 20.0), "gap_mm": Range(0.0, 1e3, unit="mm"),
          "field_mT": Range(0.0, 2000.0, low_open=True, unit="mT"), "operate_mT": FIELD_MT, "release_mT": FIELD_MT,
          "eccentricity_mm": Range(0.0, 1e3, unit="mm"), "b_offset_deg": Range(0.0, 360.0, high_open=True, unit="deg"),
          "b_offset_pitches": Range(0, 100000, integer=True), "speed_rpm": Range(0.0, 1e6, low_open=True, unit="rpm")}
"""Physical ranges of the numeric options (checked before any work, see :mod:`quenchsim.bearings.commands.ranges`)."""


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("task", choices=("field", "remanence", "pulses"),
                        help="field: B at the gaps; remanence: B_r implied by a field at a gap; pulses: Hall switching")
    parser.add_argument("--pole-width-mm", type=float, default=None, help="pole width p along the circumference, mm")
    parser.add_argument("--poles", type=int, default=None, help="number of poles (north + south)")
    parser.add_argument("--magnet-diameter-mm", type=float, default=None, help="magnetised diameter, mm")
    parser.add_argument("--thickness-mm", type=float, required=True, help="magnet thickness h, mm")
    parser.add_argument("--remanence-T", type=float, default=None, help="remanence B_r, T")
    parser.add_argument("--recoil-permeability", type=float, default=1.0, help="recoil permeability mu_r (default 1)")
    parser.add_argument("--backing", choices=("air", "iron"), default="air", help="air, or an ideal iron back plate")
    parser.add_argument("--gap-mm", type=float, nargs="+", required=True, help="air gap(s) to the sensor, mm")
    parser.add_argument("--field-mT", type=float, default=None, help="remanence: the field measured at --gap-mm, mT")
    parser.add_argument("--operate-mT", type=float, default=None, help="Hall operate point (switches on), mT")
    parser.add_argument("--release-mT", type=float, default=None, help="pulses: Hall release point (switches off), mT")
    parser.add_argument("--eccentricity-mm", type=float, default=0.0, help="pulses: ring centre offset, mm")
    parser.add_argument("--b-offset-deg", type=float, default=90.0, help="pulses: sensor B downstream of A, electrical deg")
    parser.add_argument("--b-offset-pitches", type=int, default=0, help="pulses: plus whole pole pairs")
    parser.add_argument("--speed-rpm", type=float, default=60.0, help="pulses: shaft speed for the periods, rpm")


def _need(args: argparse.Namespace, *names: str) -> None:
    for name in names:
        if getattr(args, name) is None:
            raise InputError("--" + name.replace("_", "-"), None, f"required for encoder {args.task}")


def _pole_width_mm(args: argparse.Namespace) -> float:
    if args.pole_width_mm is not None:
        return args.pole_width_mm
    if args.poles is None or args.magnet_diameter_mm is None:
        raise InputError("--pole-width-mm", None, "give it, or --poles with --magnet-diameter-mm")
    return math.pi * args.magnet_diameter_mm / args.poles


def run(args: argparse.Namespace) -> dict:
    p_mm = _pole_width_mm(args)
    common = {"pole_width_mm": p_mm, "thickness_mm": args.thickness_mm, "recoil_permeability": args.recoil_permeability,
              "backing": args.backing}
    if args.task == "remanence":
        _need(args, "field_mT")
        if len(args.gap_mm) != 1:
            raise InputError("--gap-mm", args.gap_mm, "give one gap, the one the field was measured at")
        br = enc.remanence_for_field_T(args.field_mT * 1e-3, args.gap_mm[0] * 1e-3, p_mm * 1e-3, args.thickness_mm * 1e-3,
                                       args.recoil_permeability, args.backing)
        return {**common, "gap_mm": args.gap_mm[0], "field_mT": args.field_mT, "remanence_T": br}
    _need(args, "remanence_T")
    if args.task == "field":
        e = enc.Encoder(p_mm * 1e-3, args.thickness_mm * 1e-3, args.remanence_T, args.recoil_permeability, args.backing)
        out = {**common, "remanence_T": args.remanence_T,
               "fields": [{"gap_mm": g, "pole_centre_mT": float(enc.pole_centre_field_T(e, g * 1e-3)) * 1e3}
                          for g in args.gap_mm]}
        if args.operate_mT is not None:
            if args.operate_mT <= 0.0:
                raise InputError("--operate-mT", args.operate_mT, "must be > 0 for the working gap")
            out["working_gap_mm"] = enc.working_gap_m(e, args.operate_mT * 1e-3) * 1e3
        return out
    _need(args, "poles", "magnet_diameter_mm", "operate_mT", "release_mT")
    if len(args.gap_mm) != 1:
        raise InputError("--gap-mm", args.gap_mm, "give one gap for the pulse train")
    if args.poles % 2:
        raise InputError("--poles", args.poles, "must be even (north and south poles alternate)")
    if args.release_mT >= args.operate_mT:
        raise InputError("--release-mT", args.release_mT, f"must be below --operate-mT = {args.operate_mT}")
    if args.eccentricity_mm >= args.gap_mm[0] + args.thickness_mm:
        raise InputError("--eccentricity-mm", args.eccentricity_mm, "must be below gap + thickness")
    ring = enc.RingEncoder(poles=args.poles, magnet_diameter_m=args.magnet_diameter_mm * 1e-3,
                           thickness_m=args.thickness_mm * 1e-3, remanence_T=args.remanence_T, gap_m=args.gap_mm[0] * 1e-3,
                           operate_T=args.operate_mT * 1e-3, release_T=args.release_mT * 1e-3,
                           recoil_permeability=args.recoil_permeability, backing=args.backing,
                           eccentricity_m=args.eccentricity_mm * 1e-3, b_offset_electrical_deg=args.b_offset_deg,
                           b_offset_pitches=args.b_offset_pitches)
    peak_mT = float(enc.pole_centre_field_T(ring.layer, ring.gap_m + ring.eccentricity_m)) * 1e3
    if args.operate_mT >= peak_mT or args.release_mT <= -peak_mT:
        raise InputError("--operate-mT" if args.operate_mT >= peak_mT else "--release-mT",
                         args.operate_mT if args.operate_mT >= peak_mT else args.release_mT,
                         f"the pole-centre field at the largest gap is +-{peak_mT:.3g} mT: the sensor would miss poles")
    m = enc.pulse_metrics(ring, args.speed_rpm)
    return {**common, "poles": args.poles, "magnet_diameter_mm": args.magnet_diameter_mm, "gap_mm": args.gap_mm[0],
            "sensor_b_offset_mm": ring.b_offset_rad * ring.radius_m * 1e3, **m.summary()}
