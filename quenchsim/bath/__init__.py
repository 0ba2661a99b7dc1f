"""Reduced bath-flow model: HTC(T_surface) of every boundary point from nozzle jets, part rotation and
oil boiling; also still-air cooling.

Public API::

    cfg = parse_bath(spec, field="quench.bath") -> BathConfig
    htc = boundary_htc(cfg, points) -> BoundaryHTC        # once per stage
    h = htc(T_surface_C)                                  # (n_points,) -> (n_points,), every iteration
    dh = htc.slope(T_surface_C)                           # dh/dT_s, for a Newton linearisation of h(T_s)(T_s - T_amb)
    air = air_htc(points, air_temperature_C, emissivity) -> BoundaryHTC

``BoundaryHTC`` carries T_grid_C (m,), h_W_m2K (n_points, m), ambient_C, velocity_m_s, segment (n_points,)
and the diagnostics length_m, leidenfrost_C, peak_C.

The ``[quench.bath]`` table (units as suffixes; condition overrides merged in before parsing)::

    quenchant = "reference_quench_oil"   # materials/quenchants/<name>.toml: a liquid (boiling-curve) oil, or a
                                         # still-bath curve from the ISO 9950 probe (a library oil)
    liquid_properties = "reference_quench_oil"  # only with a still-bath curve: the liquid file whose properties
                                         # and boiling-curve constants the flow uses (default shown)
    oil_temperature_C = 60.0             # bulk oil; must lie below the (liquid's) boiling point
    agitation = "flow"                   # "still": no nozzles, rotation or flow (those keys are then errors)
    agitation_m_s = 0.0                  # bulk oil speed past every face (tank agitator), 0-10 m/s, default 0
    support = "turntable"                # "turntable" | "fixture" (bottom face partly covered) | "hanging"
    support_open_fraction = 0.5          # share of the bottom face open to the oil on a turntable/fixture (0-1);
                                         # older name turntable_open_fraction
    rotation_rpm = 11.0                  # turntable speed (>= 0), default 0
    id_jet_speed_mm_s = 1000.0           # exit speed of every "id" row without its own jet_speed_mm_s (>= 0)
    od_jet_speed_mm_s = 5340.0           # same for "od" rows
    layout = "reference_nozzles"         # materials/baths/<name>.toml (kind = "nozzle_layout"): the nozzle rows with
                                         # priors (instead of [quench.bath.nozzles.*] tables; not both)
    constants = "jet_bath"               # materials/baths/<name>.toml (kind = "bath_constants"), default jet_bath: the
                                         # declared flow constants below, each with a prior; a case key overrides one
    oil_swirl_fraction = 0.05            # share of the part's rotation the oil outside the ring follows (0-1)
    bore_swirl_fraction = 0.5            # share of the bore's rotation the oil column in the bore follows (0-1)
    corner_carryover = 0.3               # share of a wall jet carried round a convex edge onto a face
                                         # turned ~90 deg from the jet (0-1)
    id_crossflow_up_m_s = 0.2            # vertical oil speed (up > 0) the "id" jets cross on their way
    od_crossflow_up_m_s = 0.0            # same for the "od" rows (-5..5 m/s)
    htc_factor = { od = 0.8 }            # factors on h(T_s) per surface (bore, od, top, bottom, or a segment name;
                                         # 0.05-20); a chamfer takes the geometric mean of its two faces'; default:
                                         # the constants file's [htc_factor] (jet_bath: 1 on every surface)
    T_max_C = 1100.0                     # top of the HTC(T) grid (clamped above), default 1100
    T_step_K = 2.0                       # grid step, default 2

    [quench.bath.nozzles.<row name>]     # any number of rows; the name's prefix id_/od_ gives the side
    side = "od"                          # optional: "id" (in the bore, aimed outward) or "od" (aimed inward)
    diameter_mm = 10.0                   # nozzle exit diameter (> 0)
    count = 12                           # nozzles in the row, evenly spaced round the part (>= 1)
    standoff_mm = 100.0                  # horizontal distance from exit to the part surface (> 0)
    height_mm = 130.0                    # nozzle height above the turntable (the part's bottom face), or
                                         # height_fraction = 0.75 of the part's height (one of the two)
    inclination_deg = 0.0                # > 0 aims the jet downward (-80..80), default 0
    jet_speed_mm_s = 5340.0              # optional: overrides <side>_jet_speed_mm_s for this row

The two reference rings name the layout ``materials/baths/reference_nozzles.toml`` and the constants
``materials/baths/jet_bath.toml`` (every assumption there with its prior, addressable by the calibration as
``layout.reference_nozzles.nozzles.<row>.<key>`` and ``bath.jet_bath.flow.<key>``).
Errors a user can cause (negative speed, oil at or above its boiling point, unknown quenchant, ...)
raise :class:`quenchsim.errors.InputError` naming the field.

Modules: quenchant (property files, Vogel viscosity), correlations (free and impinging jets, convection, boiling,
critical flux, film collapse), config (the table, layout and constants files), flow (local speed, run length and
impinging-jet shape per point), htc (boiling curve, BoundaryHTC, air), segments (per-segment tables, jet
response), outline (simple section outlines and the ISO 9950 probe for diagnostics), plots.
"""

from quenchsim.bath.config import BathConfig, NozzleRow, check_bath_keys, parse_bath
from quenchsim.bath.htc import BoundaryHTC, air_htc, boundary_htc

__all__ = ["BathConfig", "NozzleRow", "BoundaryHTC", "check_bath_keys", "parse_bath", "boundary_htc", "air_htc"]
