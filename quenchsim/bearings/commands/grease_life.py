"""`quenchsim bearings grease-life`: L50 grease life of a sealed ball bearing (urea / lithium soap).

    quenchsim bearings grease-life --grease urea --base-oil pao+ester --bearing 6204 --speed 10000 \
        [--outer-ring-rotation] --temperature 120 --load-ratio 0.03 [--weibull-slope 1.5] --json
"""

from __future__ import annotations

import argparse
import math

from quenchsim.bearings import grease, kinematics as kin
from quenchsim.bearings.commands.ranges import CONTACT_ANGLE_DEG, DIAMETER_MM, Range
from quenchsim.errors import InputError

RANGES = {"dm": DIAMETER_MM, "ball_diameter_mm": DIAMETER_MM, "contact_angle_deg": CONTACT_ANGLE_DEG,
          "speed": Range(0.0, 1e6, low_open=True, unit="rpm"),
          # the grease model's own bounds (quenchsim.bearings.grease.grease_life): no grease survives above 250 C
          "temperature": Range(-60.0, 250.0, unit="C"),
          "load_ratio": Range(0.0, 1.0, high_open=True),
          "weibull_slope": Range(0.0, 100.0, low_open=True)}
"""Physical ranges of the numeric options (checked before any work, see :mod:`quenchsim.bearings.commands.ranges`)."""


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--grease", required=True, help=f"thickener: {' | '.join(grease.grease_types())}")
    parser.add_argument("--base-oil", required=True,
                        help="mineral, pao, ester, ether, diester, silicone or a mixture joined by '+'")
    where = parser.add_mutually_exclusive_group(required=True)
    where.add_argument("--bearing", help=f"bearing from the built-in table ({', '.join(kin.bearing_names())})")
    where.add_argument("--dm", type=float, help="pitch diameter d_m, mm")
    parser.add_argument("--ball-diameter-mm", type=float, default=None,
                        help="ball diameter (with --dm and --outer-ring-rotation), mm")
    parser.add_argument("--contact-angle-deg", type=float, default=0.0,
                        help="contact angle (with --dm and --outer-ring-rotation), deg")
    parser.add_argument("--speed", type=float, required=True, help="rotating-ring speed N, rpm")
    parser.add_argument("--outer-ring-rotation", action="store_true",
                        help="the outer ring rotates (K from the cage speed)")
    parser.add_argument("--temperature", type=float, required=True, help="bearing (outer-ring) temperature, C")
    parser.add_argument("--load-ratio", type=float, required=True, help="P/Cr, equivalent load over dynamic rating")
    parser.add_argument("--weibull-slope", type=float, default=None, help="Weibull slope: adds L10_h")


def run(args: argparse.Namespace) -> dict:
    geometry: kin.BearingGeometry | None
    if args.bearing is not None:
        geometry = kin.bearing(args.bearing).geometry
        dm_mm = geometry.pitch_diameter_m * 1e3
    else:
        dm_mm = args.dm
        geometry = None
        if args.outer_ring_rotation:
            if args.ball_diameter_mm is None:
                raise InputError("--ball-diameter-mm", None,
                                 "needed with --dm and --outer-ring-rotation (or use --bearing)")
            geometry = kin.BearingGeometry(dm_mm * 1e-3, args.ball_diameter_mm * 1e-3, 1,
                                           math.radians(args.contact_angle_deg))
    K = kin.equivalent_inner_speed_factor(geometry) if args.outer_ring_rotation and geometry else 1.0
    r = grease.grease_life(args.grease, args.base_oil, dm_mm, args.speed, args.temperature, args.load_ratio, K)
    out = {"L50_h": r.L50_h, "K": r.K, "dmN": r.dmN, "within_validity": r.within_validity,
           "warnings": list(r.warnings), "grease": args.grease, "base_oil": args.base_oil,
           "base_oil_factor": r.base_oil_factor, "dm_mm": dm_mm, "speed_rpm": args.speed,
           "outer_ring_rotation": bool(args.outer_ring_rotation)}
    if args.weibull_slope is not None:
        out["L10_h"] = grease.weibull_life(r.L50_h, args.weibull_slope, 0.9)
    return out
