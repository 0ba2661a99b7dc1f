"""How far the unmeasured SUJ3 inputs move ring A's dimension change.

The reference report used measured SUJ3 flow and TRIP data that are not published; ours are 100Cr6/52100
literature values with stated uncertainties (materials/SUJ3.mechanics.toml header). This page perturbs
one input at a time by its stated 1-sigma uncertainty (or switches a mechanism off) and reruns case A,
condition 1, on the mesh x2 of the convergence study (its dimensions agree with the default mesh to
0.002 mm, quench/convergence), so a user can see which measurement would pin the prediction down.

``run(workdir)`` writes each perturbed material as a complete TOML file (material + [mechanics])
under ``runs/validation/sensitivity`` and runs what is not cached (same resolved case and same material
text). The measured change is the target (open: the baseline grows where the ring shrank).
"""

from __future__ import annotations

import copy
import hashlib
import json
import math
from collections.abc import Callable
from pathlib import Path
from typing import Any

import tomli_w

from quenchsim.materials import load_material
from quenchsim.validation import cached_run, refined_case, study_module, study_targets

TITLE = "Sensitivity of ring A's dimension change to the unmeasured SUJ3 inputs"
SLOW = True
MESH_FACTOR = 2.0


def _scaled(spec: Any, factor: float) -> Any:
    """A property spec (number, {value}, {poly_T_C}, {T_C, value}) with its values times ``factor``."""
    if isinstance(spec, (int, float)):
        return spec * factor
    out = dict(spec)
    for key in ("value", "poly_T_C"):
        if key in out:
            v = out[key]
            out[key] = [x * factor for x in v] if isinstance(v, list) else v * factor
    return out


def _scale_phases(table: dict[str, Any], factor: float, phases: tuple[str, ...] | None = None) -> None:
    per = table["per_phase"]
    for phase in list(per):
        if phases is None or phase in phases:
            per[phase] = _scaled(per[phase], factor)


def _austenite_yield(f: float) -> Callable[[dict], None]:
    return lambda m: _scale_phases(m["mechanics"]["plastic"]["yield_Pa"], f, ("austenite",))


def _trip(f: float) -> Callable[[dict], None]:
    return lambda m: _scale_phases(m["mechanics"]["trip"]["K_1_Pa"], f)


def _hardening(f: float) -> Callable[[dict], None]:
    return lambda m: _scale_phases(m["mechanics"]["plastic"]["hardening_Pa"], f)


def _pearlite_rate(f: float) -> Callable[[dict], None]:
    def change(m: dict) -> None:
        m["kinetics"]["pearlite"]["ln_F"]["const"] -= math.log(f)   # tau ~ F: rate x f
    return change


def _no_transformation(m: dict) -> None:
    """Austenite to room temperature: diffusional TTT times x e^60, Ms 450 K lower (below -200 C)."""
    m["kinetics"]["pearlite"]["ln_F"]["const"] += 60.0
    m["kinetics"]["bainite"]["ln_F"]["const"] += 60.0
    m["kinetics"]["martensite"]["Ms_formula"]["const"] -= 450.0


UNIFORM_HTC_W_M2K = 3000.0
"""A plain oil-quench level (between the bath model's ID and OD convection values)."""
UNIFORM_HTC = {"quench.htc_model": "table", "quench.bath": None,
               "quench.htc_table": {"T_C": [0.0, 900.0], "h_W_m2K": [UNIFORM_HTC_W_M2K] * 2, "ambient_C": 60.0}}

# (label, what it is and why that size, material change, case overrides)
VARIANTS: list[tuple[str, str, Callable[[dict], None] | None, dict[str, Any]]] = [
    ("baseline", "materials/SUJ3 as shipped", None, {}),
    ("austenite yield x1.4", "+1 sigma (+-40 %) of the austenite yield stress", _austenite_yield(1.4), {}),
    ("austenite yield x0.6", "-1 sigma", _austenite_yield(0.6), {}),
    ("hardening moduli x2", "+1 sigma (factor 2) of every phase's hardening modulus", _hardening(2.0), {}),
    ("hardening moduli /2", "-1 sigma", _hardening(0.5), {}),
    ("TRIP K x1.6", "+1 sigma (factor 1.6) of every TRIP constant", _trip(1.6), {}),
    ("TRIP K /1.6", "-1 sigma", _trip(1 / 1.6), {}),
    ("pearlite rate x3", "Li-model TTT times /3 (composition-based TTT models: ~80 % of steels within x3, "
     "Saunders et al.)", _pearlite_rate(3.0), {}),
    ("no TRIP", "transformation plasticity switched off", None, {"mechanics.trip": False}),
    ("thermo-elastic", "plasticity and TRIP switched off: the phase volumes alone", None,
     {"mechanics.trip": False, "mechanics.plasticity": False}),
    ("no transformation", "austenite kept to room temperature (thermal strain only): thermal-type distortion",
     _no_transformation, {}),
    ("no transformation, thermo-elastic", "the same without plasticity: the free austenite contraction alone",
     _no_transformation, {"mechanics.trip": False, "mechanics.plasticity": False}),
    ("no transformation, uniform HTC", f"as 'no transformation' with one HTC of {UNIFORM_HTC_W_M2K:g} W/m2K on every "
     "face instead of the bath model", _no_transformation, UNIFORM_HTC),
    ("no transformation, uniform HTC, thermo-elastic", "the same without plasticity", _no_transformation,
     {**UNIFORM_HTC, "mechanics.trip": False, "mechanics.plasticity": False}),
]


def _material_file(change: Callable[[dict], None], folder: Path) -> Path:
    material = copy.deepcopy(load_material("SUJ3"))
    change(material)
    text = tomli_w.dumps(material)
    path = folder / f"SUJ3_{hashlib.sha1(text.encode()).hexdigest()[:10]}.toml"
    folder.mkdir(parents=True, exist_ok=True)
    if not path.is_file():
        path.write_text(text)
    return path


def run(workdir: Path) -> dict[str, Any]:
    ring_a = study_module("quench/ring_a")
    runs_dir = ring_a.run_dirs(workdir)
    folder = Path(runs_dir) / "sensitivity"
    measured = {k: study_targets(__file__)[f"baseline_change_mm.{k}"].value for k in ("id", "od")}
    rows: dict[str, dict[str, Any]] = {}
    for label, _, change, overrides in VARIANTS:
        case = refined_case(ring_a.CASE_A, "1", mesh=MESH_FACTOR)
        tag = f"crb_outer_ring_1_mesh{MESH_FACTOR:g}"
        if change is not None:
            path = _material_file(change, folder)
            case = case.with_overrides({"material": str(path.resolve())})
            tag = f"sensitivity/{path.stem}"
        case = case.with_overrides(overrides)
        if overrides:
            tag += "_" + hashlib.sha1(repr(sorted(overrides.items())).encode()).hexdigest()[:8]
        summary = json.loads((cached_run(case, Path(runs_dir) / tag) / "summary.json").read_text())
        rows[label] = summary
    base = rows["baseline"]["dimensions_mm"]["change"]
    md = ["Case A, condition 1, mesh x2 "
          "(dimensions within 0.002 mm of the default mesh, quench/convergence). One input at a time, by its "
          "stated 1-sigma uncertainty (materials/SUJ3.mechanics.toml header) or switched off.", "",
          f"Measured change: ID {measured['id']:+.2f} mm, OD {measured['od']:+.2f} mm "
          "(reference report, Table 3: targets below).", "",
          "| variant | what | ID change mm | OD change mm | width change mm | dID vs baseline | dOD vs baseline "
          "| martensite mean | pearlite mean / max | P1 t(500 C) s |",
          "|---|---|---|---|---|---|---|---|---|---|"]
    for label, what, _, _ in VARIANTS:
        s = rows[label]
        c = s["dimensions_mm"]["change"]
        ph = s["phases_final"]
        md.append(f"| {label} | {what} | {c['id']:+.3f} | {c['od']:+.3f} | {c['width']:+.3f} | "
                  f"{c['id'] - base['id']:+.3f} | {c['od'] - base['od']:+.3f} | {ph['martensite']['mean']:.3f} | "
                  f"{ph['pearlite']['mean']:.3f} / {ph['pearlite']['max']:.3f} | "
                  f"{s['probes']['P1']['t_to_500C_s']:.1f} |")
    elastic = rows["thermo-elastic"]["dimensions_mm"]["change"]
    def thermal_type(label: str) -> dict[str, float]:  # plastic minus thermo-elastic, no transformation
        plastic, elastic_ = rows[label]["dimensions_mm"]["change"], rows[label + ", thermo-elastic"]["dimensions_mm"]["change"]
        return {k: plastic[k] - elastic_[k] for k in base}

    thermal, uniform = thermal_type("no transformation"), thermal_type("no transformation, uniform HTC")
    largest = max(abs(rows[label]["dimensions_mm"]["change"]["id"] - base["id"])
                  for label, _, change, _ in VARIANTS if change not in (None, _no_transformation))
    md += ["", "How to read it:",
           f"* The thermo-elastic row is the phase-volume part alone (ID {elastic['id']:+.3f}, OD {elastic['od']:+.3f} mm): "
           "martensite grows the ring, retained austenite shrinks it. Everything between that row and the "
           "baseline is plastic flow and TRIP, i.e. governed by the flow and TRIP data that were not measured for SUJ3.",
           "* A perturbation whose |dID| or |dOD| is comparable with the 0.15 mm tolerance of the regression target "
           "is an input that must be measured before the target can be a prediction rather than a fit.",
           f"* To meet the measurement, plastic flow and TRIP would have to change the dimensions by "
           f"{measured['id'] - elastic['id']:+.2f} mm (ID) / {measured['od'] - elastic['od']:+.2f} mm (OD) "
           f"beyond the phase volumes; in the baseline they give {base['id'] - elastic['id']:+.2f} / "
           f"{base['od'] - elastic['od']:+.2f} mm, and the largest single 1-sigma perturbation above moves ID by "
           f"{largest:.2f} mm. The measured shrinkage is therefore not within one-at-a-time reach of the stated "
           "uncertainties: either several inputs sit at the edge of their ranges together, or the kinetics/volume "
           "data differ (the report saw a ferrite-pearlite layer that these kinetics do not produce; faster pearlite "
           "alone makes this ring grow more, row 'pearlite rate x3').",
           f"* Thermal-type distortion alone (no transformation; the difference of the two 'no transformation' rows): "
           f"ID {thermal['id']:+.3f}, OD {thermal['od']:+.3f}, width {thermal['width']:+.3f} mm. Under the bath's "
           "cooling (OD jets 5x the ID jets) the hot austenite's plastic flow alone already makes the ring grow, "
           "not shrink: with these austenite flow data, thermal-type distortion cannot supply the measured shrinkage. "
           f"Under one uniform HTC of {UNIFORM_HTC_W_M2K:g} W/m2K the same comparison gives ID {uniform['id']:+.3f}, "
           f"OD {uniform['od']:+.3f}, width {uniform['width']:+.3f} mm: the growth comes from the uneven cooling.", ""]
    changes = {label: rows[label]["dimensions_mm"]["change"] for label, _, _, _ in VARIANTS}
    return {"baseline_change_mm": base, "variants_change_mm": changes,
            "largest_one_sigma_id_shift_mm": largest, "page_md": "\n".join(md)}


def page(metrics: dict[str, Any]) -> str:
    return metrics["page_md"]
