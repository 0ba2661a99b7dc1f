"""DOJ internal forces: the reference runs of Hayama (2001) on an assumed geometry, with the checks the paper allows.

The paper's three clearance cases at 10 deg (its Fig. 8) and case 3 at 2.5 / 5 / 10 deg (its Fig. 9), each over one
revolution in 2-deg steps; Eq. 12 and the rigid limit, torque transmission, six-fold symmetry, the clearance -> 0
trend and the paper's qualitative statements (targets.toml).
"""

from __future__ import annotations

import dataclasses
import math
import pathlib
import time

import numpy as np

from quenchsim.bearings.doj import (DOJModel, contact_stiffness, reference_case, reference_data, reference_geometry,
                                    scaled_reference_geometry)
from quenchsim.bearings.doj.axial import axial_force_summary
from quenchsim.bearings.doj.output import Revolution, harmonic_amplitude, plot_polar, plot_runs, summary
from quenchsim.errors import SolverError

TITLE = "DOJ internal forces: quasi-static six-ball double-offset joint with Hertz contacts and clearances"
SLOW = True

STEP_DEG = 2.0
RUNS = (("1", 10.0), ("2", 10.0), ("3", 10.0), ("3", 5.0), ("3", 2.5))
# axial force: friction coefficient of the first-order estimate (an assumption: the paper neglects friction; 0.05-0.1
# is the range given for friction contacts in oil, Modelica Standard Library Rotational.Components.Clutch)
AXIAL_FRICTION = 0.1
# convergence over the range issue 49 asks: contact angles 30-45 deg, pitch radii 25-35 mm (spheres moved with the
# pitch circle), case 3 at 10 deg
CONTACT_ANGLES_DEG = (30.0, 35.0, 40.0, 45.0)
PITCH_RADII_MM = (25.0, 27.0, 30.0, 35.0)


def _convergence(torque: float) -> dict:
    rows, failures = [], 0
    for alpha in CONTACT_ANGLES_DEG:
        for pcr in PITCH_RADII_MM:
            geo = dataclasses.replace(scaled_reference_geometry(pcr), track_contact_angle_deg=alpha)
            start = time.perf_counter()
            try:
                model = DOJModel(geo, reference_case("3"), 10.0, torque)
                phases = model.revolution(np.arange(0.0, 360.0 + 1e-9, STEP_DEG))
                rev = Revolution.from_phases(phases, model.p_n)
                rows.append({"contact_angle_deg": alpha, "pitch_circle_radius_mm": pcr, "converged": True,
                             "largest_residual": max(r.residual for r in phases),
                             "p_outer_max_over_p_n": float(rev.p_outer_N.max() / rev.p_n_N),
                             "seconds": time.perf_counter() - start})
            except SolverError as exc:
                failures += 1
                rows.append({"contact_angle_deg": alpha, "pitch_circle_radius_mm": pcr, "converged": False,
                             "error": str(exc), "seconds": time.perf_counter() - start})
    return {"rows": rows, "failures": failures, "cases": len(rows)}


def _revolution(geo, case: str, angle: float, torque: float) -> tuple[Revolution, float]:
    model = DOJModel(geo, reference_case(case), angle, torque)
    start = time.perf_counter()
    phases = model.revolution(np.arange(0.0, 360.0 + 1e-9, STEP_DEG))
    return Revolution.from_phases(phases, model.p_n), time.perf_counter() - start


def _symmetry(rev: Revolution) -> float:
    shift = int(round(60.0 / STEP_DEG))
    d_ball = np.abs(rev.p_outer_N[shift:, :-1] - rev.p_outer_N[:-shift, 1:]).max()
    d_cage = np.abs(rev.f_inner_cage_N[shift:] - rev.f_inner_cage_N[:-shift]).max()
    return float(max(d_ball, d_cage) / rev.p_n_N)


def _eq12(geo, torque: float) -> dict:
    model = DOJModel(geo, reference_case("1"), 0.0, torque)
    a, b = model.solve(0.0), model.solve(23.0)
    stiff_k = dataclasses.replace(model.k, track=model.k.track * 1e3, window=model.k.window * 1e3)
    stiff = DOJModel(geo, reference_case("1"), 0.0, torque, stiffness=stiff_k).solve(0.0)
    spread = max(np.abs(r.p_inner_N / a.p_inner_N[0] - 1.0).max() for r in (a, b))
    return {"p_n_N": model.p_n, "ratio": float(a.p_inner_N[0] / model.p_n),
            "rigid_limit_ratio": float(stiff.p_inner_N[0] / model.p_n), "ball_spread": float(spread),
            "window_over_p_n": float(np.abs(a.p_window_N).max() / model.p_n),
            "sphere_over_p_n": float(max(a.f_inner_cage_N, a.f_cage_outer_N) / model.p_n)}


def _clearance_trend(geo, torque: float) -> dict:
    base = DOJModel(geo, reference_case("1"), 10.0, torque)
    ref = base.solve(0.0)
    state, rows = ref.state, []
    for factor in (0.001, 0.01, 0.1, 0.2, 0.4, 0.7, 1.0):
        res = DOJModel(geo, reference_case("3").scaled(factor), 10.0, torque).solve(0.0, state)
        state = res.state
        rows.append({"factor": factor, "max_change_over_p_n": float(np.abs(res.p_outer_N - ref.p_outer_N).max()
                                                                    / base.p_n)})
    case2 = DOJModel(geo, reference_case("2"), 10.0, torque).solve(0.0, ref.state)
    d = {r["factor"]: r["max_change_over_p_n"] for r in rows}
    return {"rows": rows, "order": math.log10(d[0.1] / d[0.01]),
            "case2_change_over_p_n": float(np.abs(case2.p_outer_N - ref.p_outer_N).max() / base.p_n)}


def run(workdir: pathlib.Path) -> dict:
    workdir = pathlib.Path(workdir)
    started = time.perf_counter()
    data = reference_data()
    torque = data["conditions"]["torque_Nm"]
    geo = reference_geometry()
    revs, runs = {}, {}
    for case, angle in RUNS:
        rev, seconds = _revolution(geo, case, angle, torque)
        key = f"case{case}_{angle:g}deg".replace(".", "p")
        revs[key] = rev
        runs[key] = {"case": case, "angle_deg": angle, "seconds": seconds, "symmetry": _symmetry(rev),
                     **summary(rev, torque), "axial": axial_force_summary(rev, AXIAL_FRICTION)}
    plot_runs({f"case {c}, 10 deg": revs[f"case{c}_10deg"] for c in ("1", "2", "3")},
              "Fig. 8 analogue: three clearance cases at 10 deg", workdir / "bearings_doj_cases.png")
    plot_runs({f"case 3, {a:g} deg": revs[f"case3_{a:g}deg".replace(".", "p")] for a in (2.5, 5.0, 10.0)},
              "Fig. 9 analogue: case 3 at 2.5 / 5 / 10 deg", workdir / "bearings_doj_angles.png")
    plot_polar(revs["case3_10deg"], "P_o / P_n of each ball vs its position (case 3, 10 deg)",
               workdir / "bearings_doj_polar.png")
    c1, c3 = revs["case1_10deg"], revs["case3_10deg"]
    both = np.isfinite(c1.wedge_angle_deg) & np.isfinite(c3.wedge_angle_deg)
    ranges = [float(np.ptp(revs[f"case3_{a}deg"].p_outer_N) / c3.p_n_N) for a in ("2p5", "5", "10")]
    f1 = c1.f_inner_cage_N
    k = contact_stiffness(geo, reference_case("3"))
    axial_pp = [runs[f"case3_{a}deg"]["axial"]["peak_to_peak_over_mu_p_n"] for a in ("2p5", "5", "10")]
    c3_harm = runs["case3_10deg"]["axial"]["harmonics_over_mu_p_n"]
    return {
        "axial": {"frictionless_max_over_p_n": max(r["axial"]["frictionless_max_over_p_n"] for r in runs.values()),
                  "case3_10deg_non_6n_over_6n": max(v for k, v in c3_harm.items() if int(k) % 6)
                  / max(v for k, v in c3_harm.items() if int(k) % 6 == 0),
                  "peak_to_peak_by_angle_over_mu_p_n": axial_pp,
                  "increasing_with_angle": float(axial_pp[0] < axial_pp[1] < axial_pp[2]),
                  "friction": AXIAL_FRICTION},
        "convergence": _convergence(torque),
        "runs": runs, "eq12": _eq12(geo, torque), "clearance_trend": _clearance_trend(geo, torque),
        "torque": {"case1_10deg_ratio_error": runs["case1_10deg"]["torque_ratio_error"]},
        "symmetry": {"max_deviation_over_p_n": max(r["symmetry"] for r in runs.values())},
        "qualitative": {
            "case3_10deg_unloaded_fraction": runs["case3_10deg"]["unloaded_ball_phase_fraction"],
            "case1_10deg_unloaded_fraction": runs["case1_10deg"]["unloaded_ball_phase_fraction"],
            "case1_f_ic_ripple": float(np.ptp(f1) / f1.mean()),
            "case3_f_ic_6_per_rev": harmonic_amplitude(c3.phase_deg, c3.f_inner_cage_N, 6) / float(c3.f_inner_cage_N.mean()),
            "angle_fluctuation_increasing": float(ranges[0] < ranges[1] < ranges[2]),
            "p_outer_range_by_angle_over_p_n": ranges,
            "wedge_clearance_difference_deg": float(np.mean(np.abs(c3.wedge_angle_deg - c1.wedge_angle_deg)[both])),
            "wedge_defined_fraction_case3": float(np.mean(np.isfinite(c3.wedge_angle_deg)))},
        "stiffness_N_mm15": dataclasses.asdict(k), "geometry": dataclasses.asdict(geo),
        "conditions": {k2: v for k2, v in data["conditions"].items() if k2 != "source"},
        "wall_time_s": time.perf_counter() - started}


def page(m: dict) -> str:
    geo, eq, trend, q = m["geometry"], m["eq12"], m["clearance_trend"], m["qualitative"]
    ax, cv = m["axial"], m["convergence"]
    data = reference_data()
    lines = [
        "Quasi-static model of the six-ball double-offset joint of Y. Hayama, \"Internal-force analysis of a DOJ "
        "with ADAMS\" (technical review No. 69, 2001, p. 97; SAE 2001-01-1161): rigid inner race (held by the shaft "
        "at the operating angle, free to wind up under the torque), cage (5 DOF) and six balls (3 DOF each); every "
        "contact a Hertz point contact Q = K delta^1.5 with the clearances of the paper's Table 1; no friction; each "
        "phase a static equilibrium (the paper ran ADAMS dynamics at 10 rpm, where the joint is quasi-static). "
        "Method, frames and the definitions of the outputs: quenchsim/bearings/doj/model.py. `quenchsim bearings doj "
        "--case 3 --angle-deg 10 --json` runs one of these revolutions.", "",
        "**The paper prints no dimension of its joint and no numerical result.** Every dimension below is assumed "
        "(quenchsim/bearings/data/doj.toml); the checks are its Eq. 12, closed-form limits and its qualitative "
        "statements. Forces are shown over P_n = T / (6 PCR sin alpha) (Eq. 12). Roles: no printed number fixes an "
        "input (there are none to fix one with); the paper's statements come from its own ADAMS simulation, so every "
        "target is a verification, and nothing on this page is validated against a measurement.", "",
        "## Assumed geometry and the printed conditions", "",
        "| quantity | value | status |", "|---|---|---|"]
    for key, value in data["geometry"].items():
        if key != "source":
            lines.append(f"| {key} | {value:g} | assumed |")
    lines += [f"| steel E, nu | {geo['youngs_modulus_Pa'] / 1e9:g} GPa, {geo['poisson']:g} | bearing steel "
              "(data/bearing_steel.toml) |",
              f"| torque T | {m['conditions']['torque_Nm']:g} N m | printed |",
              f"| speed | {m['conditions']['speed_rpm']:g} rpm | printed (not used: quasi-static) |",
              "| operating angles | 2.5, 5, 10 deg | printed |", "",
              "| Table 1 case | track (PCD) | window | outer sphere | inner sphere |", "|---|---|---|---|---|"]
    for name, c in data["cases"].items():
        lines.append(f"| {name} ({c['label']}) | {c['track_mm']:g} | {c['window_mm']:g} | {c['outer_sphere_mm']:g} | "
                     f"{c['inner_sphere_mm']:g} |")
    st = m["stiffness_N_mm15"]
    lines += ["", "How the clearances enter (an interpretation, data/doj.toml): track = radial play of a ball between "
              "the inner and outer tracks; window = the gap of both window faces together (negative squeezes the "
              "ball); spheres = differences of radii. Contact radii: the physical ones (straight track infinite along "
              "it, flat window), not the paper's printed r_bx = r_by; Hertz stiffness by exact elliptic integrals (N/mm^1.5): "
              f"ball-track {st['track']:.4g}, ball-window {st['window']:.4g}, inner sphere {st['inner_sphere']:.4g}, "
              f"outer sphere {st['outer_sphere']:.4g} (case 3; a zero radius difference is floored at 1 um). The "
              "paper's curve fits for k, F, E give a stiffness 3.3 % above exact Hertz for a sphere on a flat and "
              "between -4.5 % and +2.1 % for radius ratios 1.5-100 (tests/bearings/test_doj.py).", "",
              "## Checks", "",
              f"* **Eq. 12** (zero angle, no clearance, P_n = {eq['p_n_N']:.1f} N): every ball carries the same force "
              f"(spread {eq['ball_spread']:.1e}), the window and sphere forces vanish ({eq['window_over_p_n']:.1e}, "
              f"{eq['sphere_over_p_n']:.1e} P_n); the force is {eq['ratio']:.4f} P_n because the Hertz deflections turn "
              "the line of action off the ideal contact angle (the groove centres are r_g - r_b = "
              f"{(geo['track_conformity'] * geo['ball_diameter_mm'] - geo['ball_diameter_mm'] / 2):.3f} mm from the "
              f"ball centre); with 1000x stiffer contacts it is {eq['rigid_limit_ratio']:.5f} P_n: Eq. 12 is the "
              "rigid limit.",
              f"* **Torque**: case 1 at 10 deg transmits T to the outer race within "
              f"{m['torque']['case1_10deg_ratio_error']:.1e} at every phase (homokinetic). With clearance the balls "
              "leave the bisecting plane and the instantaneous torque ratio departs from 1 by up to "
              f"{m['runs']['case3_10deg']['torque_ratio_error']:.2%} (case 3, 10 deg).",
              f"* **Six-fold symmetry**: ball i at phase + 60 deg equals ball i + 1 at phase, F_ic repeats every 60 deg, "
              f"in every run to {m['symmetry']['max_deviation_over_p_n']:.1e} P_n.",
              "* **Clearance -> 0** (10 deg, phase 0, case 3's clearances times a factor, from case 1): the largest "
              "change of a ball's P_o: " + ", ".join(f"x{r['factor']:g}: {r['max_change_over_p_n']:.4f}"
                                                     for r in trend['rows']) +
              f" P_n (proportional at small factors: order {trend['order']:.3f}); case 2: "
              f"{trend['case2_change_over_p_n']:.3f} P_n.", "",
              "## Reference runs", "",
              "| run | P_o / P_n min-max | P_p / P_n min-max | F_ic / P_n min-max | F_co / P_n min-max | wedge deg min-max "
              "| ball-phases unloaded | F_ic 6/rev / P_n | torque ratio error | time s |",
              "|---|---|---|---|---|---|---|---|---|---|"]
    for key, r in m["runs"].items():
        w = r["wedge_angle_deg"]
        lines.append(f"| case {r['case']}, {r['angle_deg']:g} deg | {r['p_outer']['min_over_p_n']:.3f} - "
                     f"{r['p_outer']['max_over_p_n']:.3f} | {r['p_window']['min_over_p_n']:.3f} - "
                     f"{r['p_window']['max_over_p_n']:.3f} | {r['f_inner_cage']['min_over_p_n']:.3f} - "
                     f"{r['f_inner_cage']['max_over_p_n']:.3f} | {r['f_cage_outer']['min_over_p_n']:.3f} - "
                     f"{r['f_cage_outer']['max_over_p_n']:.3f} | {w['min']:.2f} - {w['max']:.2f} | "
                     f"{r['unloaded_ball_phase_fraction']:.2f} | {r['f_inner_cage_6_per_rev_over_p_n']:.4f} | "
                     f"{r['torque_ratio_error']:.1e} | {r['seconds']:.0f} |")
    lines += ["", "![three clearance cases](bearings_doj_cases.png)", "", "![case 3 at three angles](bearings_doj_angles.png)",
              "", "![polar](bearings_doj_polar.png)", "",
              "## The paper's statements", "",
              f"* Unloaded balls with clearance: case 3 at 10 deg has no outer-track force on "
              f"{q['case3_10deg_unloaded_fraction']:.0%} of the ball-phases (case 1: {q['case1_10deg_unloaded_fraction']:.0%}); "
              f"the wedge angle is then undefined (defined on {q['wedge_defined_fraction_case3']:.0%} of case 3's ball-phases), "
              "the gaps of the paper's 10-deg curve.",
              f"* F_ic is almost constant without clearance ((max - min) / mean {q['case1_f_ic_ripple']:.4f} for case 1) "
              f"and carries a 6-per-rev wave with clearance (amplitude {q['case3_f_ic_6_per_rev']:.2f} of its mean, case 3).",
              "* A larger operating angle gives a larger fluctuation: the range of P_o over the revolution is "
              + " / ".join(f"{v:.3f}" for v in q["p_outer_range_by_angle_over_p_n"]) + " P_n at 2.5 / 5 / 10 deg.",
              f"* The wedge angle and clearance: mean |case 3 - case 1| where both are defined = "
              f"{q['wedge_clearance_difference_deg']:.2f} deg (the paper: hardly depends on clearance).", "",
              "## Axial force on the outer race over a revolution (the generated axial force)", "",
              "The outer race's tracks and bore are parallel to its axis, so the frictionless model pushes it only "
              "radially and circumferentially: its axial force is "
              f"{ax['frictionless_max_over_p_n']:.1e} P_n at every phase of every run -- a plunging joint's axial "
              "force comes from friction. Friction as an option (quenchsim/bearings/doj/axial.py, CLI `--friction`): "
              "Coulomb friction mu at the ball - outer-track contacts to first order (on the frictionless normal "
              "forces), each ball sliding along its track as the articulated joint turns, F = mu sum_i P_o,i "
              f"sign(cos psi_i). With mu = {ax['friction']:g} (assumed: 0.05-0.1 in oil):", "",
              "| run | mean / (mu P_n) | peak-to-peak / (mu P_n) | order 6 / (mu P_n) | order 12 / (mu P_n) | "
              "dominant order | peak-to-peak N |", "|---|---|---|---|---|---|---|"]
    for key, r in m["runs"].items():
        a = r["axial"]
        lines.append(f"| case {r['case']}, {r['angle_deg']:g} deg | {a['mean_over_mu_p_n']:.4f} | "
                     f"{a['peak_to_peak_over_mu_p_n']:.4f} | {a['harmonics_over_mu_p_n']['6']:.4f} | "
                     f"{a['harmonics_over_mu_p_n']['12']:.4f} | {a['dominant_order']} | {a['peak_to_peak_N']:.2f} |")
    lines += ["",
              "Order: only multiples of 6 per revolution (largest other harmonic "
              f"{ax['case3_10deg_non_6n_over_6n']:.1e} of the 6n ones, case 3 at 10 deg) -- the paper's '6th-order "
              "generated axial force' (sec. 3.2), which it expects from F_ic's 6-per-rev wave; here it comes from the "
              "balls' load variation, which that wave follows. Amplitude: grows with the operating angle ("
              + " / ".join(f"{v:.3f}" for v in ax["peak_to_peak_by_angle_over_mu_p_n"]) +
              " mu P_n peak to peak at 2.5 / 5 / 10 deg, case 3) and with the clearance (case 1 at 10 deg: "
              f"{m['runs']['case1_10deg']['axial']['peak_to_peak_over_mu_p_n']:.4f}), and is linear in mu and in the "
              "torque. No published measurement of a DOJ's axial force was found to compare the amplitude with "
              "(searched: DOJ / double-offset / ball-type plunging joint generated axial force, 6th order, friction; "
              "the published GAF measurements found are of tripod joints, e.g. Sugiura et al., J. Syst. Des. Dyn. 3 "
              "(2009) 957; Lee et al., Appl. Sci. 11 (2021) 8836), so only the order and the trends are checked.", "",
              "## Convergence over contact angles and pitch radii", "",
              f"Case 3 at 10 deg over contact angles {', '.join(f'{a:g}' for a in CONTACT_ANGLES_DEG)} deg and pitch "
              f"radii {', '.join(f'{p:g}' for p in PITCH_RADII_MM)} mm (the inner-race and cage spheres moved with "
              "the pitch circle, `scaled_reference_geometry`): "
              f"{cv['cases'] - cv['failures']} of {cv['cases']} revolutions converge (each phase to 1e-9 P_n). The "
              "solver starts a revolution by a homotopy from the joint without clearance at zero angle when the "
              "direct start stalls, restarts a stalled Levenberg-Marquardt with Jacobian scaling, and starts from a "
              "nearby phase when the first one sits where a contact opens; what still fails is refused with a "
              "one-line error naming the phases tried.", "",
              "| contact angle deg | " + " | ".join(f"PCR {p:g} mm" for p in PITCH_RADII_MM) + " |",
              "|---|" + "---|" * len(PITCH_RADII_MM)]
    for alpha in CONTACT_ANGLES_DEG:
        cells = []
        for row in cv["rows"]:
            if row["contact_angle_deg"] == alpha:
                cells.append(f"{row['largest_residual']:.0e}, P_o max {row['p_outer_max_over_p_n']:.2f} P_n, "
                             f"{row['seconds']:.0f} s" if row["converged"] else "refused")
        lines.append(f"| {alpha:g} | " + " | ".join(cells) + " |")
    lines += ["",
              f"Study run in {m['wall_time_s']:.0f} s wall time (machine shared with other jobs).", ""]
    return "\n".join(lines)
