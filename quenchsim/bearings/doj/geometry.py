"""Geometry, clearances and load of a six-ball double-offset constant-velocity joint (DOJ).

The joint of Hayama (technical review No. 69, 2001, p. 97; docs/reference/other_seed_systems.md sec. 1): an outer
race with a cylindrical bore and six straight tracks parallel to its axis, an inner race with an outer sphere and six
straight tracks parallel to the shaft, six balls, and a cage whose inner sphere sits on the inner-race sphere and whose
outer sphere sits in the outer-race bore; the two cage sphere centres lie on the cage axis at equal offsets on either
side of the window plane (the "double offset"). The paper prints the conditions and the clearances (Table 1), no
dimension: every dimension is assumed (data/doj.toml says which).
"""

from __future__ import annotations

import dataclasses
import functools
import math
from dataclasses import dataclass
from typing import Any

from quenchsim.bearings.kinematics import steel_properties
from quenchsim.errors import require
from quenchsim.inputs.reader import read_package_toml


@dataclass(frozen=True)
class DOJGeometry:
    """Dimensions in mm and degrees (see data/doj.toml: all assumed); steel E (Pa) and nu for every part."""

    pitch_circle_radius_mm: float
    ball_diameter_mm: float
    track_contact_angle_deg: float
    track_conformity: float
    inner_race_sphere_radius_mm: float
    cage_outer_sphere_radius_mm: float
    cage_offset_mm: float
    youngs_modulus_Pa: float = 2.08e11
    poisson: float = 0.3
    balls: int = 6

    def __post_init__(self) -> None:
        r = self.ball_diameter_mm / 2.0
        require(self.balls == 6, "balls", self.balls, "must be 6 (the six-ball DOJ)")
        require(math.isfinite(self.ball_diameter_mm) and self.ball_diameter_mm > 0.0, "ball_diameter_mm",
                self.ball_diameter_mm, "must be > 0")
        require(math.isfinite(self.pitch_circle_radius_mm) and self.pitch_circle_radius_mm > 2.0 * r,
                "pitch_circle_radius_mm", self.pitch_circle_radius_mm,
                f"must exceed the ball diameter {self.ball_diameter_mm:g} mm (balls must not overlap the axis)")
        require(0.0 < self.track_contact_angle_deg < 90.0, "track_contact_angle_deg", self.track_contact_angle_deg,
                "must be in (0, 90) deg (from the radial direction)")
        require(0.5 < self.track_conformity < 1.0, "track_conformity", self.track_conformity,
                "must be in (0.5, 1) (groove radius / ball diameter)")
        require(0.0 < self.inner_race_sphere_radius_mm < self.pitch_circle_radius_mm, "inner_race_sphere_radius_mm",
                self.inner_race_sphere_radius_mm, f"must be in (0, {self.pitch_circle_radius_mm:g}) mm (inside the "
                "ball pitch circle)")
        require(self.pitch_circle_radius_mm < self.cage_outer_sphere_radius_mm < self.pitch_circle_radius_mm + r,
                "cage_outer_sphere_radius_mm", self.cage_outer_sphere_radius_mm,
                f"must be in ({self.pitch_circle_radius_mm:g}, {self.pitch_circle_radius_mm + r:g}) mm (outside the "
                "pitch circle, inside the balls' outer edge)")
        require(0.0 < self.cage_offset_mm < self.inner_race_sphere_radius_mm, "cage_offset_mm", self.cage_offset_mm,
                f"must be in (0, {self.inner_race_sphere_radius_mm:g}) mm")

    @property
    def ball_radius_mm(self) -> float:
        return self.ball_diameter_mm / 2.0

    @property
    def groove_radius_mm(self) -> float:
        return self.track_conformity * self.ball_diameter_mm


@dataclass(frozen=True)
class Clearances:
    """Table 1 of the paper, mm (positive clearance, negative interference); see data/doj.toml for how each enters."""

    track_mm: float = 0.0
    window_mm: float = 0.0
    outer_sphere_mm: float = 0.0
    inner_sphere_mm: float = 0.0

    def __post_init__(self) -> None:
        for name in ("track_mm", "outer_sphere_mm", "inner_sphere_mm"):
            value = getattr(self, name)
            require(math.isfinite(value) and 0.0 <= value <= 1.0, f"clearances.{name}", value,
                    "must be in [0, 1] mm (a clearance; interference only for the window)")
        require(math.isfinite(self.window_mm) and -0.1 <= self.window_mm <= 1.0, "clearances.window_mm",
                self.window_mm, "must be in [-0.1, 1] mm (negative: the window squeezes the ball)")

    def scaled(self, factor: float) -> "Clearances":
        """Every clearance times ``factor`` (the clearance -> 0 trend of the paper's sec. 3.1)."""
        return Clearances(self.track_mm * factor, self.window_mm * factor, self.outer_sphere_mm * factor,
                          self.inner_sphere_mm * factor)


@functools.cache
def reference_data() -> dict[str, Any]:
    """data/doj.toml: the paper's conditions and Table 1 (printed) and the assumed geometry."""
    return read_package_toml("quenchsim.bearings", "data/doj.toml")


def reference_geometry() -> DOJGeometry:
    """The assumed geometry of data/doj.toml with bearing steel (data/bearing_steel.toml)."""
    g = {k: v for k, v in reference_data()["geometry"].items() if k != "source"}
    steel = steel_properties()
    return DOJGeometry(**g, youngs_modulus_Pa=steel["youngs_modulus_Pa"], poisson=steel["poisson"])


def scaled_reference_geometry(pitch_circle_radius_mm: float | None = None) -> DOJGeometry:
    """The assumed geometry with its ball pitch-circle radius moved to ``pitch_circle_radius_mm`` (None: unchanged);
    the inner-race sphere and the cage's outer sphere move with it, keeping their radial distances from the pitch
    circle (3 mm inside, 3 mm outside in data/doj.toml), so the cage stays around the balls."""
    geo = reference_geometry()
    if pitch_circle_radius_mm is None:
        return geo
    shift = pitch_circle_radius_mm - geo.pitch_circle_radius_mm
    return dataclasses.replace(geo, pitch_circle_radius_mm=pitch_circle_radius_mm,
                               inner_race_sphere_radius_mm=geo.inner_race_sphere_radius_mm + shift,
                               cage_outer_sphere_radius_mm=geo.cage_outer_sphere_radius_mm + shift)


def reference_case(case: str) -> Clearances:
    """Clearances of Table 1 case ``case`` ("1", "2" or "3")."""
    cases = reference_data()["cases"]
    require(case in cases, "case", case, f"must be one of {', '.join(cases)} (Table 1)")
    return Clearances(**{k: v for k, v in cases[case].items() if k.endswith("_mm")})
