"""`quenchsim bearings roller-clutch`: roller load, contact stresses and outer-ring response of a two-way
roller clutch at one or more transmitted torques.

    quenchsim bearings roller-clutch --torque 1152 2646 --rollers 10 --roller-diameter-mm 10.50 \
        --roller-length-mm 20.91 --bore-diameter-mm 95 --outer-diameter-mm 128 --ring-width-mm 27.2 \
        --free-wedge-angle-deg 8.39 [--friction 0.1] [--rigid] [--fe] --json

The free wedge angle is the angle between the cam flat's normal and the bore radius through the roller
centre with the roller touching both races unloaded; --rigid ignores the elastic take-up. Material: bearing
steel (data/bearing_steel.toml) unless --E-GPa/--nu. Each state reports the static safety factor of both contacts
against ISO 76's 4000 MPa (brinelling) and, with --friction, the wedge-hold check.
"""

from __future__ import annotations

import argparse
import math

from quenchsim.bearings import roller_clutch as rc
from quenchsim.bearings.commands.ranges import DIAMETER_MM, Range
from quenchsim.bearings.kinematics import steel_properties
from quenchsim.errors import InputError

RANGES = {"torque": Range(0.0, 1e7, low_open=True, unit="N m"), "rollers": Range(2, 200, integer=True),
          "roller_diameter_mm": DIAMETER_MM, "roller_length_mm": DIAMETER_MM, "bore_diameter_mm": DIAMETER_MM,
          "outer_diameter_mm": DIAMETER_MM, "ring_width_mm": DIAMETER_MM,
          "free_wedge_angle_deg": Range(0.0, 60.0, low_open=True, high_open=True, unit="deg"),
          "friction": Range(0.0, 2.0, low_open=True),
          "E_GPa": Range(0.0, 1500.0, low_open=True, unit="GPa"), "nu": Range(-1.0, 0.5, low_open=True)}
"""Physical ranges of the numeric options (checked before any work, see :mod:`quenchsim.bearings.commands.ranges`)."""


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--torque", type=float, nargs="+", required=True, help="transmitted torque(s), N m")
    parser.add_argument("--rollers", type=int, required=True, help="number of rollers (cam flats)")
    parser.add_argument("--roller-diameter-mm", type=float, required=True, help="roller diameter, mm")
    parser.add_argument("--roller-length-mm", type=float, required=True, help="effective contact length, mm")
    parser.add_argument("--bore-diameter-mm", type=float, required=True, help="outer-race bore diameter, mm")
    parser.add_argument("--outer-diameter-mm", type=float, required=True, help="outer-race outside diameter, mm")
    parser.add_argument("--ring-width-mm", type=float, required=True,
                        help="axial width of the outer ring carrying the roller loads, mm")
    parser.add_argument("--free-wedge-angle-deg", type=float, required=True,
                        help="wedge angle between flat normal and bore radius, unloaded, deg")
    parser.add_argument("--friction", type=float, default=None,
                        help="friction coefficient at the roller contacts: the wedge-hold check (tan(eps/2) <= mu), "
                        "its margin and the torque at which the rollers would slip")
    parser.add_argument("--rigid", action="store_true", help="ignore the elastic take-up of contacts and ring")
    parser.add_argument("--fe", action="store_true", help="add the plane-stress FE check of the ring (~10-30 s)")
    parser.add_argument("--E-GPa", type=float, default=None, help="Young's modulus (default: bearing steel)")
    parser.add_argument("--nu", type=float, default=None, help="Poisson's ratio (default: bearing steel)")


def run(args: argparse.Namespace) -> dict:
    steel = steel_properties()
    E = steel["youngs_modulus_Pa"] if args.E_GPa is None else args.E_GPa * 1e9
    nu = steel["poisson"] if args.nu is None else args.nu
    if args.bore_diameter_mm <= 2.0 * args.roller_diameter_mm:
        raise InputError("--bore-diameter-mm", args.bore_diameter_mm,
                         f"must exceed twice --roller-diameter-mm = {args.roller_diameter_mm} mm")
    if args.outer_diameter_mm <= args.bore_diameter_mm:
        raise InputError("--outer-diameter-mm", args.outer_diameter_mm,
                         f"must exceed --bore-diameter-mm = {args.bore_diameter_mm} mm")
    pitch_mm = math.pi * (args.bore_diameter_mm - args.roller_diameter_mm)
    if args.rollers * args.roller_diameter_mm >= pitch_mm:
        raise InputError("--rollers", args.rollers, f"{args.rollers} rollers of {args.roller_diameter_mm} mm do not "
                         f"fit on the {pitch_mm:.1f} mm pitch circle")
    g = rc.ClutchGeometry(rollers=args.rollers, roller_diameter_m=args.roller_diameter_mm * 1e-3,
                          roller_length_m=args.roller_length_mm * 1e-3, bore_diameter_m=args.bore_diameter_mm * 1e-3,
                          outer_diameter_m=args.outer_diameter_mm * 1e-3, ring_width_m=args.ring_width_mm * 1e-3,
                          free_wedge_angle_rad=math.radians(args.free_wedge_angle_deg), E_Pa=E, nu=nu)
    states = []
    for torque in args.torque:
        state = rc.analyse(g, torque, compliant=not args.rigid)
        row = state.summary()
        if args.friction is not None:
            hold = rc.wedge_hold(g, torque, args.friction, compliant=not args.rigid)
            row["friction"] = args.friction
            row["wedged"] = bool(hold.holds)
            row["wedge_hold"] = {"required_friction": hold.required_friction, "margin": hold.margin,
                                 "slip_torque_Nm": hold.slip_torque_Nm if math.isfinite(hold.slip_torque_Nm) else None}
        if args.fe:
            check = rc.fe_check(g, state)
            row["fe_check"] = {"differences_pct": check.differences_pct(), "triangles": check.triangles}
        states.append(row)
    return {"cam_offset_mm": g.cam_offset_m * 1e3, "compliant": not args.rigid, "E_GPa": E / 1e9, "nu": nu,
            "states": states}
