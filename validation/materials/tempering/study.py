"""The tempering model of 1C-Cr bearing steel (materials/data/tempering_1C_Cr.toml, quenchsim/metallurgy/tempering.py)
against published tempering data, on through-hardened specimens (no section: the metallurgy alone): hardness after
tempering, the stages of a dilatometer's heating curve, the retained austenite's decomposition and its growth, and
two closed-form checks (the relaxation update, a service hold)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from quenchsim.materials import load_material
from quenchsim.mechanics import load_mechanics
from quenchsim.mechanics.constitutive import M_VEC, return_map
from quenchsim.mechanics.model import transformation_strain
from quenchsim.metallurgy import hv_to_hrc, load_kinetics, load_tempering, phase_hardness_HV
from quenchsim.metallurgy.tempering import (AUSTENITE_REACTION, FAST_RATE_C_S, hollomon_jaffe_advance,
                                            service_change, specimen_austenite, specimen_hardness_HV)

TITLE = "Tempering of 1C-Cr bearing steel: hardness, dilatometry stages, retained austenite, relaxation, stability"
SLOW = False
STEEL = "SUJ2"
T_AUST_C = 845.0
HEATING_K_MIN = 5.0
"""Heating rate of the simulated dilatometer run (a usual rate of tempering dilatometry)."""


def _steel(T_aust_C: float = T_AUST_C) -> tuple[Any, Any, Any]:
    material = load_material(STEEL)
    kin = load_kinetics(material, T_aust_C)
    return material, kin, load_tempering(material, load_kinetics(material, T_AUST_C))


def specimen_HRC(T_C: float, time_h: float, T_aust_C: float) -> float:
    """HRC of a through-hardened specimen (austenitised at ``T_aust_C``, oil quenched to 25 C) after an isothermal
    temper."""
    material, kin, tempering = _steel(T_aust_C)
    P = tempering.parameter_after(T_C, time_h)
    hv_m = min(float(phase_hardness_HV(kin, "martensite", np.array([FAST_RATE_C_S]))[0]),
               float(tempering.tempered_martensite_HV(P)))
    return float(hv_to_hrc(specimen_hardness_HV(tempering, kin, 25.0, P, hv_m)))


def dilatometry(workdir: Path) -> dict[str, Any]:
    """Continuous heating of a through-hardened specimen at HEATING_K_MIN from 25 to 450 C: the length change of
    each reaction and the temperatures at which each is 5, 50 and 95 % done."""
    material, kin, tempering = _steel()
    T = np.arange(25.0, 450.01, 1.0)
    dt_s = 60.0 / HEATING_K_MIN
    P = np.zeros(len(T))
    for i in range(1, len(T)):
        P[i] = hollomon_jaffe_advance(np.array([P[i - 1]]), T[i - 1], T[i], dt_s, tempering.clock_constant)[0]
    x_a0 = specimen_austenite(kin, 25.0)
    model = load_mechanics(material, {"plasticity": False, "trip": False, "austenitizing_T_C": T_AUST_C})
    reaction = tempering.reactions[AUSTENITE_REACTION]
    gamma = float(transformation_strain(model, reaction.product or "bainite", 25.0))
    strains, stages = {}, {}
    for name, r in tempering.reactions.items():
        progress = r.process.progress(P)
        strains[name] = (x_a0 * gamma if r.parent == "austenite" else (1.0 - x_a0) * r.strain_per_parent) * progress
        stages[name] = {f"T{int(q * 100)}_C": float(np.interp(q, progress, T)) for q in (0.05, 0.5, 0.95)}
        stages[name]["length_change_ppm"] = float(1e6 * strains[name][-1])
    total = sum(strains.values())
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4))
    for name, e in strains.items():
        ax.plot(T, 1e6 * e, label=name.replace("_", " "))
    ax.plot(T, 1e6 * total, "k", lw=2, label="total (tempering part of the length change)")
    ax.set_xlabel("temperature (C)"), ax.set_ylabel("length change (ppm)")
    ax.set_title(f"{STEEL} hardened from {T_AUST_C:g} C, heated at {HEATING_K_MIN:g} K/min (thermal expansion removed)")
    ax.legend(fontsize=8), ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(Path(workdir) / "tempering_dilatometry.png", dpi=110)
    plt.close(fig)
    return {"stages": stages, "retained_austenite_as_quenched": x_a0, "austenite_to_bainite_strain": gamma,
            "growth_per_percent_RA": gamma * 0.01,
            "expansion_after_first_contraction_K": stages[AUSTENITE_REACTION]["T50_C"]
            - stages["martensite_transition_carbide"]["T50_C"],
            "second_contraction_after_expansion_K": stages["martensite_cementite"]["T50_C"]
            - stages[AUSTENITE_REACTION]["T50_C"]}


def relaxation_closed_form() -> dict[str, float]:
    """At a fixed total strain the stress update with the relaxation's viscous term (3 mu dPhi = exp(dr) - 1, the
    solver's) against the closed form exp(-r), in 1 and in 37 unequal steps to r = 1.3."""
    shear, bulk = 80e9, 170e9
    eps = np.array([[1e-3, -4e-4, -6e-4, 2e-4]])
    s0 = return_map(eps, np.array([bulk]), np.array([shear]), None, None, None).stress
    out = {}
    for n in (1, 37):
        r = np.cumsum(np.linspace(1.0, 3.0, n))
        r = 1.3 * r / r[-1]
        e, last = eps.copy(), 0.0
        for ri in r:
            d_phi = np.expm1(np.array([ri - last])) / (3.0 * shear)
            update = return_map(e, np.array([bulk]), np.array([shear]), None, None, d_phi)
            e = e - update.d_trip_strain
            last = ri
        dev = lambda s: s - (s @ M_VEC / 3.0)[..., None] * M_VEC  # noqa: E731
        out[f"deviatoric_ratio_{n}_steps"] = float(np.linalg.norm(dev(update.stress)) / np.linalg.norm(dev(s0)))
    out["closed_form"] = float(np.exp(-1.3))
    return out


def stability_closed_form() -> dict[str, Any]:
    """A point tempered 2 h at 180 C (10 % austenite at the temper's start, 90 % martensite) held at 100, 120 and
    150 C for 1 and 10 years: :func:`service_change` (the closed form of the clock) against the clock integrated in
    10,000 steps by additivity (:func:`hollomon_jaffe_advance`)."""
    _, _, tempering = _steel()
    P0 = np.array([tempering.parameter_after(180.0, 2.0)])
    r = tempering.reactions[AUSTENITE_REACTION].process
    austenite = 0.1 * (1.0 - r.progress(P0))
    out: dict[str, Any] = {}
    for T in (100.0, 120.0, 150.0):
        for years in (1.0, 10.0):
            hours = years * 8766.0
            change = service_change(tempering, P0, np.array([0.9]), austenite, T, hours)
            P = P0.copy()
            for _ in range(10000):
                P = hollomon_jaffe_advance(P, T, T, hours * 3600.0 / 10000, tempering.clock_constant)
            stepped = 0.1 * (r.progress(P) - r.progress(P0))
            out[f"{T:g}C_{years:g}y"] = {"austenite_decomposed": float(change.austenite_decomposed[0]),
                                        "stepped": float(stepped[0]),
                                        "relative_difference": float(abs(change.austenite_decomposed[0] - stepped[0])
                                                                     / max(stepped[0], 1e-30))}
    out["max_relative_difference"] = max(v["relative_difference"] for v in out.values() if isinstance(v, dict))
    return out


def run(workdir: Path) -> dict[str, Any]:
    hardness: dict[str, Any] = {"crucible": {}, "en31": {}}
    for T in (150, 205, 260, 315, 370):
        hardness["crucible"][str(T)] = specimen_HRC(float(T), 2.0, 815.0)
    for T in (150, 200, 250, 300):
        hardness["en31"][str(T)] = specimen_HRC(float(T), 1.0, 815.0)
    hardness["asm_150C_2h"] = specimen_HRC(150.0, 2.0, 845.0)
    hardness["asm_230C_4h"] = specimen_HRC(230.0, 4.0, 845.0)
    _, _, tempering = _steel()
    r = tempering.reactions[AUSTENITE_REACTION].process
    ra = {"decomposed_220C_6h": float(r.progress(tempering.parameter_after(220.0, 6.0))),
          "decomposed_235C_2h": float(r.progress(tempering.parameter_after(235.0, 2.0))),
          "decomposed_180C_2h": float(r.progress(tempering.parameter_after(180.0, 2.0))),
          "T50_1h_C": float(r.P50_K / tempering.clock_constant - 273.15)}
    return {"hollomon_jaffe_constant": tempering.clock_constant,
            "tempered_martensite_HV_poly_P_kK": list(tempering.hardness_poly_HV),
            "hardness_HRC": hardness, "dilatometry": dilatometry(workdir), "retained_austenite": ra,
            "relaxation": relaxation_closed_form(), "stability": stability_closed_form()}


def page(metrics: dict[str, Any]) -> str:
    h, d = metrics["hardness_HRC"], metrics["dilatometry"]
    c = metrics["tempered_martensite_HV_poly_P_kK"]
    md = [f"Hollomon-Jaffe constant C = {metrics['hollomon_jaffe_constant']:.2f} (t in h); tempered martensite "
          f"HV_TM = {c[0]:.0f} + ({c[1]:.1f}) p + ({c[2]:.2f}) p^2 with p = P / 1000 K "
          "(fitted to the Crucible table, the calibration).", "",
          "### Hardness after tempering (through-hardened specimens)", "",
          "| table | temperature C | time h | model HRC |", "|---|---|---|---|"]
    md += [f"| Crucible 52100 (calibration), from 815 C | {T} | 2 | {v:.1f} |" for T, v in h["crucible"].items()]
    md += [f"| EN31 supplier table (validation), from 815 C | {T} | 1 | {v:.1f} |" for T, v in h["en31"].items()]
    md += ["", f"### Dilatometry: continuous heating at {HEATING_K_MIN:g} K/min", "",
           "![dilatometry](tempering_dilatometry.png)", "",
           "| reaction | 5 % at C | 50 % at C | 95 % at C | length change ppm |", "|---|---|---|---|---|"]
    for name, s in d["stages"].items():
        md.append(f"| {name.replace('_', ' ')} | {s['T5_C']:.0f} | {s['T50_C']:.0f} | {s['T95_C']:.0f} | "
                  f"{s['length_change_ppm']:+.0f} |")
    md += ["", f"Retained austenite of the specimen as quenched: {d['retained_austenite_as_quenched']:.3f}; its "
           f"decomposition grows the specimen by {1e6 * d['growth_per_percent_RA']:.0f} ppm per 1 % (the stress "
           "model's austenite -> bainite strain at room temperature).", "",
           "No dilatometer curve of a 1C-Cr bearing steel could be read (docs/experiments/tempering_search.md): the "
           "stage ranges are compared with the printed ranges of Fe-C and medium-carbon martensite and of tool steels.",
           "", "### Service stability (closed-form check)", "",
           "| hold | austenite decomposed (closed form) | stepped clock |", "|---|---|---|"]
    for k, v in metrics["stability"].items():
        if isinstance(v, dict):
            md.append(f"| {k.replace('_', ', ')} | {v['austenite_decomposed']:.5f} | {v['stepped']:.5f} |")
    md += ["", "Bearing makers' stabilisation classes (SN to 120 C, S0 150 C, S1 200 C ...) name the highest service "
           "temperature at which a ring of that class keeps its size; they print no size change, so they give no "
           "number to compare with."]
    return "\n".join(md)
