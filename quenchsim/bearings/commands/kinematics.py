"""`quenchsim bearings kinematics`: cage, ball-spin and ball-pass frequencies of a ball bearing.

    quenchsim bearings kinematics --bearing 6204 --inner-rpm 1800 [--outer-rpm 0] [--measured-cage-rpm R] --json
    quenchsim bearings kinematics --pitch-diameter-mm 39.04 --ball-diameter-mm 7.94 --balls 9 --inner-rpm 1797

The geometry options are shared with the hertz and free-run verbs.
"""

from __future__ import annotations

import argparse
import math
from dataclasses import asdict

from quenchsim.bearings import kinematics as kin
from quenchsim.bearings.commands.ranges import GEOMETRY, SPEED_RPM
from quenchsim.errors import InputError, require

RANGES = {**GEOMETRY, "inner_rpm": SPEED_RPM, "outer_rpm": SPEED_RPM, "measured_cage_rpm": SPEED_RPM}
"""Physical ranges of the numeric options (checked before any work, see :mod:`quenchsim.bearings.commands.ranges`)."""


def add_geometry_arguments(parser: argparse.ArgumentParser, required: bool = True) -> None:
    """--bearing NAME or --pitch-diameter-mm/--ball-diameter-mm/--balls [--contact-angle-deg]."""
    g = parser.add_argument_group("bearing geometry (a table bearing or explicit dimensions)")
    g.add_argument("--bearing", help=f"bearing from the built-in table ({', '.join(kin.bearing_names())})")
    g.add_argument("--pitch-diameter-mm", type=float, help="pitch diameter d_m, mm")
    g.add_argument("--ball-diameter-mm", type=float, help="ball diameter D, mm")
    g.add_argument("--balls", type=int, help="number of balls Z")
    g.add_argument("--contact-angle-deg", type=float, default=None,
                   help="contact angle, deg (default: the table value, or 0)")
    parser.set_defaults(_geometry_required=required)


def geometry_from_args(args: argparse.Namespace) -> tuple[kin.BearingGeometry | None, kin.BearingData | None]:
    """The geometry (and table row, if --bearing) named by the geometry options, or (None, None)."""
    explicit = [args.pitch_diameter_mm, args.ball_diameter_mm, args.balls]
    if args.bearing is not None:
        if any(v is not None for v in explicit):
            raise InputError("--bearing", args.bearing, "give either --bearing or explicit dimensions, not both")
        data = kin.bearing(args.bearing)
        geometry = data.geometry
        if args.contact_angle_deg is not None:
            geometry = kin.BearingGeometry(geometry.pitch_diameter_m, geometry.ball_diameter_m, geometry.balls,
                                           math.radians(args.contact_angle_deg))
        return geometry, data
    if all(v is None for v in explicit):
        if args._geometry_required:
            raise InputError("--bearing", None, "give --bearing NAME or --pitch-diameter-mm, --ball-diameter-mm "
                             "and --balls")
        return None, None
    for name, v in zip(("--pitch-diameter-mm", "--ball-diameter-mm", "--balls"), explicit):
        if v is None:
            raise InputError(name, None, "required with explicit bearing dimensions")
    require(args.ball_diameter_mm < args.pitch_diameter_mm, "--ball-diameter-mm", args.ball_diameter_mm,
            f"must be < --pitch-diameter-mm = {args.pitch_diameter_mm:g} mm")
    require(args.balls * args.ball_diameter_mm < math.pi * args.pitch_diameter_mm, "--balls", args.balls,
            f"must fit on the pitch circle: balls x ball diameter < pi x pitch diameter = "
            f"{math.pi * args.pitch_diameter_mm:.4g} mm")
    angle = math.radians(args.contact_angle_deg or 0.0)
    return kin.BearingGeometry(args.pitch_diameter_mm * 1e-3, args.ball_diameter_mm * 1e-3, args.balls, angle), None


def configure(parser: argparse.ArgumentParser) -> None:
    add_geometry_arguments(parser)
    parser.add_argument("--inner-rpm", type=float, default=0.0, help="inner-ring speed, rpm (signed)")
    parser.add_argument("--outer-rpm", type=float, default=0.0, help="outer-ring speed, rpm (signed)")
    parser.add_argument("--measured-cage-rpm", type=float, default=None,
                        help="measured cage speed, rpm: adds the slip ratio C_s = (1 - N_c/N_tc) 100 %%")


def run(args: argparse.Namespace) -> dict:
    geometry, data = geometry_from_args(args)
    assert geometry is not None  # configure() makes the geometry options required: geometry_from_args raised otherwise
    f = kin.frequencies(geometry, args.inner_rpm / 60.0, args.outer_rpm / 60.0)
    relative_hz = abs(args.inner_rpm - args.outer_rpm) / 60.0
    out: dict = {"bearing": data.name if data else None, "inner_rpm": args.inner_rpm, "outer_rpm": args.outer_rpm,
                 **asdict(f),
                 "orders_of_relative_speed": ({k: v / relative_hz for k, v in asdict(f).items()}
                                              if relative_hz > 0.0 else None),
                 "cage_rpm": f.cage_hz * 60.0,
                 "K_outer_ring_rotation": kin.equivalent_inner_speed_factor(geometry),
                 "geometry": {"pitch_diameter_m": geometry.pitch_diameter_m,
                              "ball_diameter_m": geometry.ball_diameter_m, "balls": geometry.balls,
                              "contact_angle_deg": math.degrees(geometry.contact_angle_rad)}}
    if args.measured_cage_rpm is not None:
        out["slip_ratio_pct"] = kin.roller_slip_ratio_pct(args.measured_cage_rpm, f.cage_hz * 60.0)
    if data is not None:
        out["source"] = data.source
    return out
