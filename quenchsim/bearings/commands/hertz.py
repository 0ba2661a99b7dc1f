"""`quenchsim bearings hertz point|line|ball-race`: Hertz contact (exact elliptic integrals).

    quenchsim bearings hertz point --load 500 --rx1-mm 4 --ry1-mm 4 --rx2-mm 12.8 --ry2-mm -4.1 --json
    quenchsim bearings hertz line --load 29812 --length-mm 20.9 --r1-mm 5.52 --r2-mm 89 --json
    quenchsim bearings hertz ball-race --bearing 6204 --inner-groove-ratio 0.515 --outer-groove-ratio 0.525 \
        --load 500 --json

Radii of curvature in mm, concave radii negative. Materials default to bearing steel
(data/bearing_steel.toml); --E1-GPa/--nu1/--E2-GPa/--nu2 override (ball-race: body 1 for balls and rings).
"""

from __future__ import annotations

import argparse
import math
from dataclasses import asdict

from quenchsim.bearings import hertz
from quenchsim.bearings.commands.kinematics import add_geometry_arguments, geometry_from_args
from quenchsim.bearings.commands.ranges import GEOMETRY, Range
from quenchsim.bearings.kinematics import steel_properties
from quenchsim.errors import InputError

RADIUS_MM = Range(-1e9, 1e9, unit="mm (concave < 0)", nonzero=True)
RANGES = {**GEOMETRY, "load": Range(0.0, unit="N"),
          **{f"{r}_mm": RADIUS_MM for r in ("rx1", "ry1", "rx2", "ry2", "r1", "r2")},
          "length_mm": Range(0.0, 1e4, low_open=True, unit="mm"),
          # the stiffest solid (diamond) has E ~ 1.2e3 GPa; an isotropic solid has -1 < nu <= 0.5
          "E1_GPa": Range(0.0, 1500.0, low_open=True, unit="GPa"),
          "E2_GPa": Range(0.0, 1500.0, low_open=True, unit="GPa"),
          "nu1": Range(-1.0, 0.5, low_open=True), "nu2": Range(-1.0, 0.5, low_open=True),
          # a groove radius must exceed the ball radius (conformity f = r / D > 0.5)
          "inner_groove_ratio": Range(0.5, 10.0, low_open=True), "outer_groove_ratio": Range(0.5, 10.0, low_open=True)}
"""Physical ranges of the numeric options (checked before any work, see :mod:`quenchsim.bearings.commands.ranges`)."""


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("contact", choices=("point", "line", "ball-race"),
                        help="point: two bodies; line: two parallel cylinders; ball-race: a ball bearing")
    parser.add_argument("--load", type=float, default=None, help="normal (ball) load, N")
    for name in ("rx1", "ry1", "rx2", "ry2"):
        parser.add_argument(f"--{name}-mm", type=float, default=None,
                            help=f"point: principal radius {name}, mm (concave < 0)")
    parser.add_argument("--length-mm", type=float, default=None, help="line: contact length, mm")
    parser.add_argument("--r1-mm", type=float, default=None, help="line: radius of body 1, mm (concave < 0)")
    parser.add_argument("--r2-mm", type=float, default=None, help="line: radius of body 2, mm (concave < 0)")
    parser.add_argument("--E1-GPa", type=float, default=None, help="Young's modulus of body 1 (default: bearing steel)")
    parser.add_argument("--nu1", type=float, default=None, help="Poisson's ratio of body 1")
    parser.add_argument("--E2-GPa", type=float, default=None, help="Young's modulus of body 2")
    parser.add_argument("--nu2", type=float, default=None, help="Poisson's ratio of body 2")
    add_geometry_arguments(parser, required=False)
    parser.add_argument("--inner-groove-ratio", type=float, default=None,
                        help="ball-race: inner groove radius / ball diameter")
    parser.add_argument("--outer-groove-ratio", type=float, default=None,
                        help="ball-race: outer groove radius / ball diameter")


def _need(args: argparse.Namespace, *names: str) -> None:
    for name in names:
        if getattr(args, name) is None:
            raise InputError("--" + name.replace("_", "-"), None,
                             f"required for a {args.contact} contact")


def _pick(value: float | None, default: float, scale: float = 1.0) -> float:
    return default if value is None else value * scale


def run(args: argparse.Namespace) -> dict:
    steel = steel_properties()
    E, nu = steel["youngs_modulus_Pa"], steel["poisson"]
    m = (_pick(args.E1_GPa, E, 1e9), _pick(args.nu1, nu), _pick(args.E2_GPa, E, 1e9), _pick(args.nu2, nu))
    if args.contact in ("point", "line"):
        r: hertz.PointContact | hertz.LineContact
        if args.contact == "point":
            _need(args, "load", "rx1_mm", "ry1_mm", "rx2_mm", "ry2_mm")
            r = hertz.point_contact(args.load, args.rx1_mm * 1e-3, args.ry1_mm * 1e-3, args.rx2_mm * 1e-3,
                                    args.ry2_mm * 1e-3, *m)
        else:
            _need(args, "load", "length_mm", "r1_mm", "r2_mm")
            r = hertz.line_contact(args.load, args.length_mm * 1e-3, args.r1_mm * 1e-3, args.r2_mm * 1e-3, *m)
        return {"contact": args.contact, "load_N": args.load, **asdict(r)}
    _need(args, "inner_groove_ratio", "outer_groove_ratio")
    geometry, data = geometry_from_args(args)
    if geometry is None:
        raise InputError("--bearing", None, "give --bearing NAME or explicit dimensions for a ball-race contact")
    E_b, nu_b = m[0], m[1]
    D, dm, a = geometry.ball_diameter_m, geometry.pitch_diameter_m, geometry.contact_angle_rad
    k = hertz.ball_race_stiffness(D, dm, a, args.inner_groove_ratio, args.outer_groove_ratio, E_b, nu_b)
    out: dict = {"contact": "ball-race", "bearing": data.name if data else None, **asdict(k),
                 "contact_angle_deg": math.degrees(a)}
    if args.load is not None:
        (rxi, ryi), (rxo, ryo) = hertz.race_radii_m(D, dm, a, args.inner_groove_ratio, args.outer_groove_ratio)
        out["load_N"] = args.load
        out["inner"] = asdict(hertz.point_contact(args.load, D / 2, D / 2, rxi, ryi, E_b, nu_b, E_b, nu_b))
        out["outer"] = asdict(hertz.point_contact(args.load, D / 2, D / 2, rxo, ryo, E_b, nu_b, E_b, nu_b))
    return out
