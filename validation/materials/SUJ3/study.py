"""SUJ3 from the closest published data (100Cr6) plus one declared calibration point: ring A conditions 1-3
(thermal + metallurgy), the P1 pearlite plateau, A485 Grade 1 Jominy minimum, SUJ3 vs SUJ2 hardenability."""

from __future__ import annotations

import csv
import pathlib

import meshio
import numpy as np

from quenchsim.case import load_case
from quenchsim.fitting import kinetics as fk
from quenchsim.fitting.diagram_data import load_diagram_data
from quenchsim.fitting.jominy import cooling_histories
from quenchsim.fitting.plots import plot_cct_overlay, plot_jominy, plot_ttt
from quenchsim.materials import load_material, materials_dir
from quenchsim.metallurgy import hv_to_hrc, load_kinetics
from quenchsim.metallurgy.cct import critical_rate_C_s
from quenchsim.pipeline import run as run_case
from quenchsim.results import last_frame

TITLE = "SUJ3: kinetics from the closest published data (100Cr6) + the ring A condition-1 calibration point"
SLOW = True
T_AUST_C = 850.0
CASE = pathlib.Path(__file__).resolve().parents[3] / "cases" / "crb_outer_ring.toml"
JOMINY_MM = np.array([1.5, 3.0, 5.0, 7.9, 10.0, 12.7, 15.9, 20.0, 25.0, 30.0, 40.0, 50.0])


def _centre_fractions(out: pathlib.Path) -> dict[str, float]:
    """Phase fractions at the section centre (P1) from the last results file."""
    m = meshio.read(last_frame(out))
    p = m.points[:, :2]
    centre = 0.5 * (p.min(axis=0) + p.max(axis=0))
    k = int(np.argmin(np.sum((p - centre) ** 2, axis=1)))
    return {n: float(m.point_data[n][k]) for n in ("austenite", "pearlite", "bainite", "martensite", "hardness_HRC")}


def wall_profile(out: pathlib.Path) -> dict[str, list[float]]:
    """Phase fractions and hardness through the wall at mid-width, from the bore (depth 0) to the OD, from the last
    results file (the nodes nearest the mid-width plane)."""
    m = meshio.read(last_frame(out))
    r, z = m.points[:, 0], m.points[:, 1]
    z_mid = 0.5 * (z.min() + z.max())
    near = np.abs(z - z_mid) <= np.sort(np.abs(z - z_mid))[min(60, z.size - 1)]
    order = np.argsort(r[near])
    names = ("pearlite", "bainite", "martensite", "austenite", "hardness_HRC")
    scale = 1e3 if r.max() < 10.0 else 1.0
    prof = {"depth_mm": (scale * (r[near][order] - r.min())).tolist()}
    prof.update({n: np.asarray(m.point_data[n])[near][order].tolist() for n in names})
    return prof


def _plot_wall(prof: dict[str, list[float]], path: pathlib.Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4))
    for n in ("pearlite", "bainite", "martensite", "austenite"):
        a.plot(prof["depth_mm"], prof[n], label=n)
    a.set_xlabel("depth below the bore at mid-width (mm)")
    a.set_ylabel("phase fraction")
    a.legend(fontsize=8)
    a.grid(lw=0.3)
    b.plot(prof["depth_mm"], prof["hardness_HRC"])
    b.axhline(58.0, color="k", lw=0.6, ls="--")
    b.set_xlabel("depth below the bore at mid-width (mm)")
    b.set_ylabel("HRC")
    b.grid(lw=0.3)
    fig.suptitle("ring A, condition 1 (calibration point): phases and hardness through the wall at mid-width")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def plateau_depth(time_s: np.ndarray, T_C: np.ndarray) -> float:
    """Largest 1 - r_min / r_after over the local minima r_min of the cooling rate between 720 and 550 C, r_after the
    largest rate after that minimum down to 500 C: > 0 when the rate dips and recovers (the latent-heat shoulder
    of a transformation), 0 when it only falls."""
    rate = -np.gradient(T_C, time_s)
    depth = 0.0
    for i in range(1, T_C.size - 1):
        if 550.0 <= T_C[i] <= 720.0 and rate[i] < rate[i - 1] and rate[i] <= rate[i + 1]:
            after = np.flatnonzero((np.arange(T_C.size) > i) & (T_C >= 500.0))
            if after.size:
                depth = max(depth, 1.0 - rate[i] / rate[after].max())
    return float(depth)


def _probe(out: pathlib.Path, name: str) -> tuple[np.ndarray, np.ndarray]:
    with (out / "probes.csv").open() as fh:
        rows = list(csv.DictReader(fh))
    return np.array([float(r["time_s"]) for r in rows]), np.array([float(r[f"{name}_C"]) for r in rows])


def run(workdir: pathlib.Path) -> dict:
    material = load_material("SUJ3")
    kin = load_kinetics(material, T_AUST_C)
    out = {}
    for cond in ("1", "2", "3"):
        case = load_case(CASE, cond, {"mechanics.enabled": False})
        res = run_case(case, workdir / f"ring_A_c{cond}", progress=False)
        h = res.summary["hardness"]
        out[f"hrc58_depth_c{cond}_mm"] = float(h["depth_mm"]["HRC58_bore_mid"])
        out[f"hrc58_depth_od_c{cond}_mm"] = float(h["depth_mm"]["HRC58_od_mid"])
        out[f"core_HRC_c{cond}"] = float(h["core_HRC"])
        out[f"bore_HRC_c{cond}"] = float(h["surface_HRC"]["bore_mid"])
        centre = _centre_fractions(workdir / f"ring_A_c{cond}")
        out[f"core_martensite_c{cond}"] = centre["martensite"]
        out[f"p1_pearlite_c{cond}"] = centre["pearlite"]
        out[f"p1_bainite_c{cond}"] = centre["bainite"]
        t, T = _probe(workdir / f"ring_A_c{cond}", "P1")
        out[f"p1_plateau_c{cond}"] = plateau_depth(t, T)
        out[f"p1_t500_c{cond}_s"] = float(res.summary["probes"]["P1"]["t_to_500C_s"])
        if cond == "1":
            _plot_p1(t, T, workdir / "SUJ3_ringA_c1_P1.png")
            prof = wall_profile(workdir / "ring_A_c1")
            _plot_wall(prof, workdir / "SUJ3_ringA_c1_wall.png")
            for d in (2.0, 5.0, 10.0, 20.0, 30.0):
                for n in ("pearlite", "bainite", "martensite", "hardness_HRC"):
                    out[f"wall_{n}_{d:g}mm_c1"] = float(np.interp(d, prof["depth_mm"], prof[n]))
    out["depth_c2_minus_c1_mm"] = out["hrc58_depth_c2_mm"] - out["hrc58_depth_c1_mm"]
    out["depth_c1_minus_c3_mm"] = out["hrc58_depth_c1_mm"] - out["hrc58_depth_c3_mm"]
    _, hv = fk.run_histories(kin, *cooling_histories(material, kin, JOMINY_MM))
    hrc = hv_to_hrc(hv)
    out["jominy_mm"], out["jominy_HRC"] = JOMINY_MM.tolist(), [float(x) for x in hrc]
    out["jominy_J10_HRC"] = float(np.interp(15.875, JOMINY_MM, hrc))
    crit3 = critical_rate_C_s(kin, 0.05, T_AUST_C)
    crit2 = critical_rate_C_s(load_kinetics(load_material("SUJ2"), T_AUST_C), 0.05, T_AUST_C)
    out["critical_rate_C_s"], out["critical_rate_ratio_SUJ3_SUJ2"] = crit3, crit3 / crit2
    data = load_diagram_data(materials_dir().parent / material["kinetics"]["fit"]["data_file"])
    out["calibration_factor_pearlite"] = data.fit["pearlite"].tau_factor
    out["calibration_factor_bainite"] = data.fit["bainite"].tau_factor
    plot_cct_overlay(kin, data, workdir / "SUJ3_cct.png")
    plot_ttt(kin, data, workdir / "SUJ3_ttt.png")
    plot_jominy(JOMINY_MM, hrc, [], workdir / "SUJ3_jominy.png", "SUJ3 model on the standard Jominy bar",
                limits=[(15.875, 46.0, "ASTM A485 Grade 1: min 46 HRC at J10")])
    return out


def _plot_p1(t: np.ndarray, T: np.ndarray, path: pathlib.Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4))
    a.plot(t, T)
    a.set_xlabel("time (s)")
    a.set_ylabel("P1 temperature (C)")
    a.set_xlim(0, 200)
    a.grid(lw=0.3)
    b.plot(T, -np.gradient(T, t))
    b.set_xlabel("P1 temperature (C)")
    b.set_ylabel("cooling rate (C/s)")
    b.invert_xaxis()
    b.set_xlim(850, 300)
    b.grid(lw=0.3)
    fig.suptitle("ring A, condition 1, section centre P1: the pearlite shoulder in the cooling rate")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def page(m: dict) -> str:
    rows = "\n".join(
        f"| {c} | {m[f'hrc58_depth_c{c}_mm']:.1f} | {m[f'hrc58_depth_od_c{c}_mm']:.1f} | {m[f'bore_HRC_c{c}']:.1f} | "
        f"{m[f'core_HRC_c{c}']:.1f} | {m[f'p1_pearlite_c{c}']:.2f} / {m[f'p1_bainite_c{c}']:.2f} / {m[f'core_martensite_c{c}']:.2f} | "
        f"{m[f'p1_plateau_c{c}']:.3f} | {m[f'p1_t500_c{c}_s']:.1f} |" for c in ("1", "2", "3"))
    wall = "\n".join(
        f"| {d:g} | {m[f'wall_pearlite_{d:g}mm_c1']:.2f} | {m[f'wall_bainite_{d:g}mm_c1']:.2f} | "
        f"{m[f'wall_martensite_{d:g}mm_c1']:.2f} | {m[f'wall_hardness_HRC_{d:g}mm_c1']:.1f} |" for d in (2, 5, 10, 20, 30))
    return f"""No numeric CCT, TTT or Jominy curve of SUJ3 or of its closest equivalents (100CrMnSi4-4, ASTM A485 Grade 1)
was found (materials/SOURCES.md). SUJ3's kinetics therefore come from the closest published data, those of 100Cr6
(Kawulok 2020 CCT, Kaymak 2007 bainite TTT; see the SUJ2 page), refitted with SUJ3's own Ae1 (719 C) and Ms, and
ONE declared calibration: the PEARLITE time scale x {m['calibration_factor_pearlite']:g} (bainite x
{m['calibration_factor_bainite']:g}: the data's own), fixed by the reference report's condition-1 reading (HRC58 about
5 mm below the raceway at mid-width). Conditions 2 and 3 and everything else below are predictions.

## Which data fixed which parameter

| parameter | fixed by |
|---|---|
| pearlite tau_ref, n; bainite tau_ref, m, Q, n, n_per_K, Bs | 100Cr6 data (same fit as SUJ2, with SUJ3's Ae1/Ms) |
| pearlite m, Q | Li et al. 1998 shape (the data cannot constrain them) |
| pearlite T_u = Ae1 719 C | ShKh15 Ac1 724 C shifted by Andrews' Ae1 composition terms |
| pearlite time-scale factor {m['calibration_factor_pearlite']:g} | CALIBRATION: ring A condition 1 HRC58 depth 5 mm (bisection with validation/materials/SUJ3/calibrate.py, jet bath, default mesh and steps: factor 0.8146 / 0.8177 / 0.8209 / 0.8272 -> 4.78 / 4.96 / 5.18 / 5.62 mm; materials/data/SUJ3_from_100Cr6.toml) |

## What the calibration says about the model

* **The factor is below 1**: to leave only 5 mm hard, the pearlite must be about 20 % faster than the 100Cr6
  data's, so the model SUJ3 is LESS hardenable than 100Cr6 (critical-rate ratio below), against the makers'
  statement that SUJ3 is the more hardenable grade. With the 100Cr6 pearlite (factor 1) ring A hardens through
  (HRC58 41 mm). Either the jet bath's absolute heat transfer is too high (its boiling peaks are 2-3x the
  measured still-oil peaks, reports/bath_model.md), or the ring's oil bath cooled more slowly than the jets'
  correlations say; the report prints no absolute cooling time to tell which.
* **The core is not ferrite-pearlite.** At the calibrated factor P1 holds {m['p1_pearlite_c1']:.2f} pearlite,
  {m['p1_bainite_c1']:.2f} bainite and {m['core_martensite_c1']:.2f} martensite, where the report describes a
  ferrite-pearlite core (target >= 0.7, missed). The search shows why: P1 reaches 0.75 pearlite only at a factor
  (0.7071, on the cold section) that leaves 2.8 mm hard; between 5 mm and the centre the wall's cooling rate changes too little for the
  pearlite to go from the ~0.35 that HRC58 allows to >= 0.7, and the austenite the pearlite leaves in the core
  passes the fast Kaymak bainite C-curve (start 8 s at 380-440 C) on the way down. Two further pearlite Avrami
  exponents were tried inside the fit's uncertainty (n = 5, 6 with tau re-fitted; bath before the Berenson fix): at
  the depth's factor P1 had 0.30 / 0.37 pearlite and 0.20 / 0.21 bainite -- no better. Not forced.
* **What a pearlitic core would ask of the cooling** (docs/experiments/process_physics.md, thermal + metallurgy
  runs): the kinetics are sharp enough (linear cooling: HRC58 at 8 C/s, 0.70 pearlite at 6 C/s), the wall is not --
  in its regular regime every point cools at nearly the same rate at a given temperature. Only about 6 kW/m2K on
  every surface through the pearlite range, with the pearlite x0.54, gives the report's picture (HRC58 5.2 mm, 0.90
  pearlite at P1); one 3 kW/m2K oil table leaves 0.49 pearlite, and Furlan's measured-fit specific heat of the
  SUJ3-like 100CrMnSi6-4 (550-600 J/kg K in hot austenite, against the printed 419 at every temperature) moves the
  factor above 1 (1.17) but turns the core bainitic (0.43-0.86).

## Through the wall, condition 1 (mid-width, from the bore)

| depth mm | pearlite | bainite | martensite | HRC |
|---|---|---|---|---|
{wall}

![phases through the wall](SUJ3_ringA_c1_wall.png)

## Ring A (thermal + metallurgy)

| condition | HRC58 depth bore (mm) | HRC58 depth OD (mm) | bore HRC | core HRC | P1 pearlite / bainite / martensite | P1 plateau | P1 t to 500 C (s) |
|---|---|---|---|---|---|---|---|
{rows}

Condition 1 is the calibration; 2 and 3 were not used. Condition 2 comes out through-hardened (HRC58 through the
wall): the report only says it hardens deeper than condition 1.

![P1 cooling](SUJ3_ringA_c1_P1.png)

## Hardenability

Critical rate (<= 5 % pearlite + bainite, 850 C): {m['critical_rate_C_s']:.1f} C/s, {m['critical_rate_ratio_SUJ3_SUJ2']:.2f} x SUJ2's.
Jominy (model): """ + ", ".join(f"J{d:g} {h:.0f}" for d, h in zip(m["jominy_mm"], m["jominy_HRC"])) + """ HRC; ASTM A485
Grade 1 asks at least 46 HRC at J10 (15.9 mm).

![CCT](SUJ3_cct.png)

![TTT](SUJ3_ttt.png)

![Jominy](SUJ3_jominy.png)
"""
