"""SUJ2 (= 100Cr6) built from published transformation data: fit quality, critical rate, TTT -> CCT cross-prediction,
hardness checks. Runs the shipped material against its data file (materials/data/100Cr6_kawulok2020_kaymak2007.toml)
and refits the bainite to the TTT alone for the cross-prediction."""

from __future__ import annotations

import dataclasses
import pathlib

import numpy as np

from quenchsim.fitting import kinetics as fk
from quenchsim.fitting.diagram_data import CoolingCurve, load_diagram_data
from quenchsim.fitting.jominy import cooling_histories
from quenchsim.fitting.plots import plot_cct_overlay, plot_jominy, plot_ttt
from quenchsim.materials import load_material, materials_dir
from quenchsim.metallurgy import hv_to_hrc, load_kinetics, phase_hardness_HV
from quenchsim.metallurgy.cct import cct_diagram, critical_rate_C_s

TITLE = "SUJ2 (100Cr6): kinetics fitted to published CCT and TTT data"
SLOW = False
T_AUST_C = 850.0
CCT_RATES_C_S = (0.2, 0.5, 1.0, 2.0, 3.0, 5.0, 8.0, 12.0, 25.0, 60.0, 150.0)
DENSE_RATES_C_S = tuple(float(x) for x in np.geomspace(0.2, 150.0, 58))
"""Kawulok's 'absence of bainite' holds at every rate of the diagram (0.2-150 C/s): the cross-prediction is checked on
20 rates per decade, not only on the data file's points (its maximum lies between 5 and 8 C/s)."""


def run(workdir: pathlib.Path) -> dict:
    material = load_material("SUJ2")
    kin = load_kinetics(material, T_AUST_C)
    data = load_diagram_data(materials_dir().parent / material["kinetics"]["fit"]["data_file"])
    res = fk.residuals(kin, data)
    # cross-prediction: bainite from the TTT alone, predicted along the CCT rates
    ttt_only = dataclasses.replace(data, cct=(), fit={"bainite": data.fit["bainite"]})
    fit_ttt = fk.fit_kinetics(ttt_only)
    kin_ttt = fit_ttt.kinetics
    curves = [CoolingCurve(T_AUST_C, 20.0, rate_C_s=r) for r in CCT_RATES_C_S]
    predicted = fk.run_curves(kin_ttt, curves).fractions["bainite"]
    dense = fk.run_curves(kin_ttt, [CoolingCurve(T_AUST_C, 20.0, rate_C_s=r) for r in DENSE_RATES_C_S]).fractions["bainite"]
    joint = fk.run_curves(kin, curves)
    start_ratio = {name: {f"{r.where.split('T_C = ')[1].rstrip(')')}": r.model / r.data for r in rows
                          if r.quantity == "bainite start time"}
                   for name, rows in (("shipped", res), ("ttt_only", fit_ttt.residuals))}
    d = cct_diagram(kin, np.array([100.0]), 840.0)
    kin840 = load_kinetics(material, 840.0)
    jominy_d = np.array([1.5, 3.0, 5.0, 7.9, 10.0, 12.7, 15.9, 20.0, 25.0, 30.0, 40.0, 50.0])
    _, jominy_hv = fk.run_histories(kin, *cooling_histories(material, kin, jominy_d))
    plot_cct_overlay(kin, data, workdir / "SUJ2_cct.png")
    plot_ttt(kin, data, workdir / "SUJ2_ttt.png")
    plot_jominy(jominy_d, hv_to_hrc(jominy_hv), [], workdir / "SUJ2_jominy.png", "SUJ2 model on the standard Jominy bar (no published 100Cr6 Jominy curve found)")
    return {
        "critical_rate_C_s": critical_rate_C_s(kin, 0.05, T_AUST_C),
        "critical_rate_1pct_C_s": critical_rate_C_s(kin, 0.01, T_AUST_C),
        "ttt_to_cct_max_bainite": float(np.max(dense)),
        "ttt_to_cct_max_bainite_rate_C_s": DENSE_RATES_C_S[int(np.argmax(dense))],
        "ttt_to_cct_critical_rate_C_s": critical_rate_C_s(kin_ttt, 0.05, T_AUST_C),
        "ttt_to_cct_bainite": {f"{r:g}": float(x) for r, x in zip(CCT_RATES_C_S, predicted)},
        "joint_fit_bainite": {f"{r:g}": float(x) for r, x in zip(CCT_RATES_C_S, joint.fractions["bainite"])},
        "joint_fit_pearlite": {f"{r:g}": float(x) for r, x in zip(CCT_RATES_C_S, joint.fractions["pearlite"])},
        "ttt_start_time_max_factor": max(max(x, 1.0 / x) for x in start_ratio["shipped"].values()),
        "ttt_only_start_time_max_factor": max(max(x, 1.0 / x) for x in start_ratio["ttt_only"].values()),
        "ttt_start_time_ratio": start_ratio,
        "fit_cost": 0.5 * float(sum(r.residual**2 for r in res)),
        "residuals": [{"point": r.where, "quantity": r.quantity, "data": r.data, "model": r.model, "unit": r.unit,
                       "normalised": r.residual} for r in res],
        "parameters": {r: {k: (v["value"] if isinstance(v, dict) else v) for k, v in material["kinetics"][r].items()
                           if k not in ("model", "source")} for r in ("pearlite", "bainite")},
        "ttt_only_bainite": {k: (list(v) if isinstance(v, tuple) else v) for k, v in fit_ttt.parameters["bainite"].items()},
        "as_quenched_HV": float(d.hardness_HV[0]),
        "as_quenched_HRC": float(d.hardness_HRC[0]),
        "martensite_HV_100_C_s": float(phase_hardness_HV(kin840, "martensite", np.array([100.0]))[0]),
        "bainite_HV_10_C_s": float(phase_hardness_HV(kin, "bainite", np.array([10.0]))[0]),
        "pearlite_HV_0.2_C_s": float(phase_hardness_HV(kin, "pearlite", np.array([0.2]))[0]),
        "Ms_C": kin.Ms_C,
        "jominy_mm": jominy_d.tolist(),
        "jominy_HRC": [float(x) for x in hv_to_hrc(jominy_hv)],
    }


def page(m: dict) -> str:
    p, b, bt = m["parameters"]["pearlite"], m["parameters"]["bainite"], m["ttt_only_bainite"]
    nodes = "/".join(f"{t:g}" for t in b["n_nodes_T_C"])
    lines = [
        "SUJ2's pearlite and bainite are `c_curve` JMAK laws, 1/tau = (1/tau_ref) [(T_u - T)/(T_u - T_ref)]^m "
        "exp[-(Q/R)(1/T - 1/T_ref)], fitted by `quenchsim material fit "
        "materials/data/100Cr6_kawulok2020_kaymak2007.toml --out materials/SUJ2.toml` through the simulation's own "
        "additivity (`metallurgy.advance`). The pearlite's Avrami exponent n is constant; the bainite's n(T) is "
        f"piecewise linear through nodes at {nodes} C (constant beyond them): the data's own exponent per temperature, "
        "ln[ln 0.01 / ln 0.99] / ln(t_finish / t_start), falls from 3.4 at 240 C to 2.7 at 350 C, stays at 2.5-2.7 up to "
        "430 C and drops to 1.7 at 440 C, in the bay below Bs where the finish line jumps to 266 s. A linear "
        "n(T) = n + n_per_K (T - T_ref) (the law shipped before) could not follow that bay and left the 440 C start "
        "1.56x off.", "",
        "## Which data fixed which parameter", "",
        "| reaction | parameter | value | fixed by |", "|---|---|---|---|",
        f"| pearlite | tau_ref_s (at {p['T_ref_C']:g} C) | {p['tau_ref_s']:.4g} s | Kawulok 2020: critical rate 12 C/s and no bainite at 0.2-150 C/s |",
        f"| pearlite | n | {p['n']:.3g} | the same CCT statements (pearlite must finish before the bainite range below the critical rate); at the Avrami bound 4 |",
        f"| pearlite | m, Q, T_u | {p['undercooling_exponent']:g}, {p['Q_J_mol']:.0f} J/mol, {p['T_upper_C']:g} C | not constrained by the data: Li et al. 1998 shape, ShKh15 Ac1 |",
        f"| bainite | tau_ref_s, m, Q, T_u | {b['tau_ref_s']:.4g} s, {b['undercooling_exponent']:.3g}, {b['Q_J_mol']:.0f} J/mol, {b['T_upper_C']:.1f} C | Kaymak 2007 TTT (42 start/finish times, 240-440 C) |",
        f"| bainite | n at {nodes} C | {', '.join(f'{x:.3g}' for x in b['n_nodes'])} | the same TTT (bounds 1-4) |",
        "",
        "## Fit and cross-prediction", "",
        f"Critical cooling rate (at most 5 % pearlite + bainite, from 850 C): **{m['critical_rate_C_s']:.1f} C/s** "
        f"(1 %: {m['critical_rate_1pct_C_s']:.1f} C/s) against Kawulok's 12 C/s.", "",
        "Isothermal 1 % bainite times, model / digitised Kaymak start line (shipped = joint CCT + TTT fit; TTT only = the "
        "bainite fitted to the 42 TTT times alone, the law of the cross-prediction below):", "",
        "| T C | " + " | ".join(m["ttt_start_time_ratio"]["shipped"]) + " |",
        "|---|" + "---|" * len(m["ttt_start_time_ratio"]["shipped"]),
        *(f"| {name} | " + " | ".join(f"{x:.2f}" for x in m["ttt_start_time_ratio"][key].values()) + " |"
          for name, key in (("shipped", "shipped"), ("TTT only", "ttt_only"))), "",
        f"Worst factor: shipped {m['ttt_start_time_max_factor']:.2f}, TTT only {m['ttt_only_start_time_max_factor']:.2f} "
        "(the issue's criterion: within 1.5).", "",
        f"TTT -> CCT: the bainite fitted to the Kaymak TTT alone (tau_ref {bt['tau_ref_s']:.4g} s, m "
        f"{bt['undercooling_exponent']:.3g}, Q {bt['Q_J_mol']:.0f} J/mol, T_u {bt['T_upper_C']:.1f} C, n "
        f"{', '.join(f'{x:.3g}' for x in bt['n_nodes'])} at {nodes} C), run along linear cooling (pearlite: the CCT-fitted "
        "law), against Kawulok's 'absence of bainite'. Largest bainite over 0.2-150 C/s (20 rates per decade): "
        f"**{m['ttt_to_cct_max_bainite']:.3f} at {m['ttt_to_cct_max_bainite_rate_C_s']:.1f} C/s**; critical rate (5 %) "
        f"with this bainite {m['ttt_to_cct_critical_rate_C_s']:.1f} C/s (its pearlite is the CCT-fitted one, so this "
        "is not an independent prediction). At the data file's rates:", "",
        "| rate C/s | " + " | ".join(m["ttt_to_cct_bainite"]) + " |",
        "|---|" + "---|" * len(m["ttt_to_cct_bainite"]),
        "| bainite, TTT-only fit | " + " | ".join(f"{x:.3f}" for x in m["ttt_to_cct_bainite"].values()) + " |",
        "| bainite, joint fit | " + " | ".join(f"{x:.3f}" for x in m["joint_fit_bainite"].values()) + " |",
        "| pearlite, joint fit | " + " | ".join(f"{x:.3f}" for x in m["joint_fit_pearlite"].values()) + " |",
        "",
        "Why the cross-prediction stays a few % above 'no bainite' with any law that follows the TTT: at 5-8 C/s the "
        "austenite left by the pearlite spends 10-20 s between 440 and 350 C, where Kaymak's 1 % start is 7.7-13 s, so "
        "the Scheil sum of dt / t_start passes 1 well above Ms whatever n(T) is (the linear n(T) shipped before: 0.062 at "
        "5.8 C/s on the same grid; piecewise n: the value above; the incubation rule of docs/experiments/incubation_rule.md gives the same start; start-weighted fits and more "
        "nodes give 0.059-0.069, docs/experiments/ttt_to_cct_bainite_laws.md; only a constant n, 1.9x off the TTT, "
        "stays under 0.05). Additivity of "
        "the isothermal incubation is what over-predicts here (or Kaymak's specimens, of unstated austenitising, are "
        "faster than Kawulok's 850 C / 10 min ones).", "",
        "The reverse prediction (CCT -> TTT) is not possible with these data: the CCT gives no bainite line to predict from.",
        "", "![CCT](SUJ2_cct.png)", "", "![TTT](SUJ2_ttt.png)", "",
        "## Hardness checks", "",
        f"As-quenched (100 C/s from 840 C): {m['as_quenched_HV']:.0f} HV = {m['as_quenched_HRC']:.1f} HRC; martensite "
        f"phase {m['martensite_HV_100_C_s']:.0f} HV (Maynier on the dissolved 0.6-0.7 %C, cap 900). Bainite phase at 10 C/s: "
        f"{m['bainite_HV_10_C_s']:.0f} HV (bulk composition, cap 645 HV from Yurtseven's 595-645 HV). Pearlite at 0.2 C/s: "
        f"{m['pearlite_HV_0.2_C_s']:.0f} HV (no published fine-pearlite hardness of 1 %C steel was found to check it). "
        f"Ms {m['Ms_C']:.0f} C.", "",
        "Jominy (model, no data): " + ", ".join(f"J{d:g} {h:.0f}" for d, h in zip(m["jominy_mm"], m["jominy_HRC"])) + " HRC.",
        "", "![Jominy](SUJ2_jominy.png)", "",
        "## Residual of every data point", "", "| point | quantity | data | model | unit | normalised |", "|---|---|---|---|---|---|",
    ]
    lines += [f"| {r['point']} | {r['quantity']} | {r['data']:.4g} | {r['model']:.4g} | {r['unit']} | {r['normalised']:.2f} |"
              for r in m["residuals"]]
    return "\n".join(lines) + "\n"
