"""SUJ2 (= 100Cr6) round bars 20/30/40 mm oil quenched from 850 C: the Lucefin 100Cr6 card's hardness traverses
PREDICTED by the full thermal + metallurgy chain (mechanics off) with the kinetics fitted to the Kawulok 2020 CCT and
the Kaymak 2007 TTT -- no fitting, no tuning. The card does not state the oil: the reference prediction is the
library accelerated oil in a still bath at its test temperature, and a bracket of other oil quenches gives the
prediction's band. Published values: targets.toml."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from quenchsim import results
from quenchsim.case import Case, load_case
from quenchsim.figures import save, subplots
from quenchsim.results.postprocess import time_to_temperature
from quenchsim.validation import Target, cached_run, study_targets

TITLE = "SUJ2 (100Cr6) round bars 20/30/40 mm, 850 C oil: predicted vs measured hardness traverses (Lucefin card)"
SLOW = True
HERE = Path(__file__).resolve().parent
CASE = HERE / "round_bar_oil.toml"
ROUNDS_MM = (20.0, 30.0, 40.0)
LENGTH_PER_DIAMETER = 4.0
"""Bar length / diameter: mid-length of a 4 x D bar is a radial problem (the length check compares 6 x D; at the
converged default step 3 x D was 0.55 HRC off 5 x D on the 40 mm round, above the check's 0.5 HRC)."""
LENGTH_CHECK_PER_DIAMETER = 6.0
CHECK_ROUND_MM = 40.0
"""The mesh and length checks use the 40 mm round: its traverse is the steepest."""
REFERENCE_BATH = "fast_oil_still_60C"
BATHS: dict[str, tuple[str, dict[str, Any]]] = {
    REFERENCE_BATH: ("library accelerated oil (ASTM D6200 fast oil), still, 60 C (its probe-test temperature)", {}),
    "fast_oil_0.5m_s_60C": ("the same oil stirred, bulk speed 0.5 m/s past the bar, 60 C",
                            {"quench.bath.agitation": "flow", "quench.bath.agitation_m_s": 0.5}),
    "reference_oil_still_60C": ("the reference quench oil (boiling-curve model of the ring report's oil), still, 60 C",
                                {"quench.bath.quenchant": "reference_quench_oil"}),
}
"""What a heat treater would call "oil quench" for a bar of this size: the bracket behind the prediction's band."""


def round_key(diameter_mm: float) -> str:
    return f"d{diameter_mm:g}"


def bar_case(diameter_mm: float, bath: str, length_per_diameter: float = LENGTH_PER_DIAMETER,
             mesh: float = 1.0) -> Case:
    """The round of ``diameter_mm`` in ``bath`` (a key of BATHS), length ``length_per_diameter`` x D, element sizes
    times ``mesh``; probes on the axis and 1 mm under the surface at mid-length."""
    length = length_per_diameter * diameter_mm
    probes = [{"name": "centre", "r_mm": 0.0, "z_mm": 0.5 * length},
              {"name": "under_surface", "r_mm": 0.5 * diameter_mm - 1.0, "z_mm": 0.5 * length}]
    case = load_case(CASE, None, {"geometry.outer_diameter_mm": diameter_mm, "geometry.width_mm": length,
                                  "probes": probes, **BATHS[bath][1]})
    return case.refined(mesh=mesh)


PHASES = ("martensite", "bainite", "pearlite", "austenite")


def radial_traverse(run: results.RunResults) -> tuple[np.ndarray, np.ndarray]:
    """(r mm from the axis, HRC) at mid-length of a solid bar: the run's traverse from the axis ("bore") side."""
    return run.hardness_traverse["depth_mm"], run.hardness_traverse["HRC_from_bore"]


def phases_at_mid_length(run: results.RunResults) -> dict[str, dict[str, float]]:
    """Final phase fractions at the node nearest the axis and the surface at mid-length (last frame)."""
    r, z = run.frame.points[:, 0], run.frame.points[:, 1]
    z_mid = 0.5 * (z.min() + z.max())
    out = {}
    for where, r_at in (("centre", 0.0), ("surface", r.max())):
        k = int(np.argmin((r - r_at) ** 2 + (z - z_mid) ** 2))
        out[where] = {p: round(float(run.frame.point_data[p][k]), 3) for p in PHASES}
    return out


def measured_points(targets: dict[str, Target], diameter_mm: float) -> dict[float, float]:
    """{r mm: HRC} of the card for one round, read from targets.toml (metrics rounds.dD.HRC_rN_mm)."""
    head = f"rounds.{round_key(diameter_mm)}.HRC_r"
    return {float(m[len(head):-len("_mm")]): t.value for m, t in targets.items() if m.startswith(head)}


BAINITE_RANGE_C = (450.0, 220.0)
"""From above the fitted bainite C-curve (Kaymak data 240-440 C) down to about SUJ2's Ms (216 C): the time a point
spends here is what the additivity integrates the bainite incubation over."""


def _probe_times(run: results.RunResults) -> dict[str, float | None]:
    """t8/5 of the centre and under-surface probes, and the time each spends in BAINITE_RANGE_C."""
    out: dict[str, float | None] = {}
    for probe in ("centre", "under_surface"):
        out[f"{probe}_t8_5_s"] = run.summary["probes"][probe]["t8_5_s"]
        hi, lo = (time_to_temperature(run.probes["time_s"], run.probes[f"{probe}_C"], T) for T in BAINITE_RANGE_C)
        out[f"{probe}_in_bainite_range_s"] = None if hi is None or lo is None else lo - hi
    return out


def _max_difference(a: tuple[np.ndarray, np.ndarray], b: tuple[np.ndarray, np.ndarray]) -> float:
    r = np.linspace(0.0, min(a[0][-1], b[0][-1]), 200)
    return float(np.max(np.abs(np.interp(r, *a) - np.interp(r, *b))))


def run(workdir: Path) -> dict[str, Any]:
    workdir.mkdir(parents=True, exist_ok=True)
    targets = study_targets(__file__)
    rounds: dict[str, Any] = {}
    traverses: dict[str, dict[str, tuple[np.ndarray, np.ndarray]]] = {}
    for D in ROUNDS_MM:
        key = round_key(D)
        points = measured_points(targets, D)
        radii = np.array(sorted(points))
        by_bath, traverses[key] = {}, {}
        for bath in BATHS:
            run = results.load(cached_run(bar_case(D, bath), workdir / f"{key}_{bath}"))
            r, hrc = radial_traverse(run)
            traverses[key][bath] = (r, hrc)
            by_bath[bath] = {"HRC_at_radii": np.round(np.interp(radii, r, hrc), 2).tolist(),
                             "core_HRC": float(hrc[0]), "surface_HRC": float(hrc[-1]), **_probe_times(run),
                             "phases": phases_at_mid_length(run)}
        at = np.array([b["HRC_at_radii"] for b in by_bath.values()])
        ref = by_bath[REFERENCE_BATH]
        rounds[key] = {**{f"HRC_r{x:g}_mm": v for x, v in zip(radii, ref["HRC_at_radii"])},
                       "radii_mm": radii.tolist(), "measured_HRC": [points[x] for x in radii],
                       "band_low_HRC": at.min(axis=0).tolist(), "band_high_HRC": at.max(axis=0).tolist(),
                       "by_bath": by_bath}
    cores = {key: rounds[key]["HRC_r0_mm"] for key in rounds}
    mass_effect = {"core_d20_minus_d30_HRC": cores["d20"] - cores["d30"],
                   "core_d30_minus_d40_HRC": cores["d30"] - cores["d40"]}
    check = round_key(CHECK_ROUND_MM)
    base = traverses[check][REFERENCE_BATH]
    fine = radial_traverse(results.load(cached_run(bar_case(CHECK_ROUND_MM, REFERENCE_BATH, mesh=0.5),
                                                   workdir / f"{check}_fine")))
    long_case = bar_case(CHECK_ROUND_MM, REFERENCE_BATH, LENGTH_CHECK_PER_DIAMETER)
    longer = radial_traverse(results.load(cached_run(long_case, workdir / f"{check}_long")))
    checks = {"mesh_max_difference_HRC": _max_difference(base, fine),
              "length_max_difference_HRC": _max_difference(base, longer)}
    plot_traverses(rounds, traverses, workdir / "SUJ2_rounds_traverses.png")
    return {"rounds": rounds, "mass_effect": mass_effect, "checks": checks, "settings": settings()}


def settings() -> dict[str, Any]:
    case = bar_case(CHECK_ROUND_MM, REFERENCE_BATH)
    keys = ("material", "process.austenitising_temperature_C", "transfer.time_s", "quench.time_s",
            "quench.bath.oil_temperature_C", "quench.bath.support", "air.temperature_C", "air.until_max_C",
            "mesh.size_mm", "mesh.surface_size_mm", "mesh.surface_layer_mm", "mechanics.enabled")
    return {"case": str(CASE.relative_to(HERE.parents[2])), "length_per_diameter": LENGTH_PER_DIAMETER,
            "baths": {k: label for k, (label, _) in BATHS.items()}, **{k: case.get(k) for k in keys}}


def plot_traverses(rounds: dict[str, Any], traverses: dict[str, dict[str, tuple[np.ndarray, np.ndarray]]],
                   path: Path) -> Path:
    """Per round: the card's points (both halves), the reference prediction and the band of the bath bracket,
    mirrored across the axis as the card prints them."""
    fig, axes = subplots(1, len(rounds), figsize=(5.0 * len(rounds), 4.2), sharey=True)
    for ax, (key, m) in zip(np.atleast_1d(axes), rounds.items()):
        r = traverses[key][REFERENCE_BATH][0]
        all_hrc = np.array([np.interp(r, *traverses[key][b]) for b in BATHS])
        x = np.concatenate([-r[::-1], r])

        def mirror(y: np.ndarray) -> np.ndarray:
            return np.concatenate([y[::-1], y])

        ax.fill_between(x, mirror(all_hrc.min(axis=0)), mirror(all_hrc.max(axis=0)), color="C0", alpha=0.2,
                        label="band: oil-quench bracket")
        ax.plot(x, mirror(all_hrc[list(BATHS).index(REFERENCE_BATH)]), "C0-", label="predicted: still fast oil 60 C")
        radii, meas = np.array(m["radii_mm"]), np.array(m["measured_HRC"])
        ax.plot(np.concatenate([-radii[::-1], radii]), np.concatenate([meas[::-1], meas]), "ks", ms=5,
                label="measured (Lucefin card)")
        ax.set(title=f"round {key[1:]} mm, 850 C, oil", xlabel="distance from the centre (mm)", ylabel="HRC")
        ax.grid(alpha=0.3)
    np.atleast_1d(axes)[0].legend(fontsize=8, loc="lower center")   # the 20 mm panel's lower half is empty
    fig.tight_layout()
    return save(fig, path)


def page(m: dict[str, Any]) -> str:
    s = m["settings"]
    lines = [
        "SUJ2's kinetics (materials/SUJ2.toml) were FITTED to the Kawulok et al. 2020 CCT of 100Cr6 (critical rate "
        "12 C/s, no bainite) and the Kaymak 2007 bainite TTT (reports/materials_SUJ2.md). The hardness traverses "
        "below, from the Lucefin Group 100Cr6 technical card (rounds 20, 30, 40 mm quenched at 850 C in oil), were "
        "used in no fit: they are predicted by the full thermal + metallurgy chain, nothing tuned.",
        "",
        f"Run: solid bars {s['length_per_diameter']:g} x D long, austenitised at "
        f"{s['process.austenitising_temperature_C']:g} C, straight into the bath "
        f"(transfer {s['transfer.time_s']:g} s), "
        f"hanging, {s['quench.time_s']:g} s in oil at {s['quench.bath.oil_temperature_C']:g} C, then still air at "
        f"{s['air.temperature_C']:g} C until the hottest point is below {s['air.until_max_C']:g} C; mechanics off; "
        f"mesh {s['mesh.size_mm']:g} mm core / {s['mesh.surface_size_mm']:g} mm in the outer "
        f"{s['mesh.surface_layer_mm']:g} mm (case `{s['case']}`). Hardness: quenchsim's phase-mixture hardness at "
        "mid-length (hardness_traverse.csv, from the axis).",
        "",
        "The card does not print the oil, its temperature or agitation. The prediction judged is the reference bath; "
        "the band is the spread over the bracket of oil quenches below (not a fit: no member was chosen for "
        "agreement):",
        "",
        *[f"- `{k}`{' (reference)' if k == REFERENCE_BATH else ''}: {label}" for k, label in s["baths"].items()],
        "",
        "| round | r (mm) | measured HRC | predicted HRC (reference) | band (bracket) |",
        "|---|---|---|---|---|",
    ]
    for key, r in m["rounds"].items():
        for i, x in enumerate(r["radii_mm"]):
            where = " (centre)" if x == 0 else (" (surface)" if i == len(r["radii_mm"]) - 1 else "")
            lines.append(f"| {key[1:]} mm | {x:g}{where} | {r['measured_HRC'][i]:g} | {r[f'HRC_r{x:g}_mm']:.1f} | "
                         f"{r['band_low_HRC'][i]:.1f}-{r['band_high_HRC'][i]:.1f} |")
    lines += ["", "Centre and 1 mm under-surface t8/5 (800 -> 500 C) per bath, s (SUJ2's fitted critical linear "
              "rate, 12 C/s, is t8/5 = 25 s):", "", "| round | " + " | ".join(BATHS) + " |",
              "|---|" + "---|" * len(BATHS)]
    for key, r in m["rounds"].items():
        cells = [f"{b['centre_t8_5_s']:.1f} / {b['under_surface_t8_5_s']:.1f}" for b in r["by_bath"].values()]
        lines.append(f"| {key[1:]} mm | " + " | ".join(cells) + " |")
    lines += ["", "Final phases at mid-length in the reference bath "
              "(martensite / bainite / pearlite / retained austenite):",
              "", "| round | centre | surface |", "|---|---|---|"]
    for key, r in m["rounds"].items():
        ph = r["by_bath"][REFERENCE_BATH]["phases"]
        cells = [" / ".join(f"{ph[w][p]:.2f}" for p in PHASES) for w in ("centre", "surface")]
        lines.append(f"| {key[1:]} mm | " + " | ".join(cells) + " |")
    d30, d40 = m["rounds"]["d30"]["by_bath"][REFERENCE_BATH], m["rounds"]["d40"]["by_bath"]
    ref40 = d40[REFERENCE_BATH]
    hi, lo = BAINITE_RANGE_C
    lines += ["", "## Reading", "",
              "The 20 mm round is predicted right: through-hardened, as measured. From 30 mm on the prediction parts "
              "from the card in kind, not only in degree. The card's 40 mm traverse falls steadily from a martensitic "
              "surface to a soft core, the profile of a martensitic case over a core that contains pearlite. The model "
              "makes the 30 and 40 mm rounds largely BAINITIC across the whole section (40 mm: "
              f"{ref40['phases']['centre']['bainite']:.0%} bainite at the centre, "
              f"{ref40['phases']['surface']['bainite']:.0%} at the surface), so the traverse is flat "
              "near the bainite hardness: too hard in the core, a little soft at the surface. Kawulok's dilatometry "
              "found no bainite in 100Cr6 at any linear rate from 0.2 to 150 C/s; the bainite here comes from the "
              "Kaymak TTT's early bainite start, integrated by Scheil additivity over the slow end of a still-oil "
              "quench (the oil's convection stage), where a bar of this size lingers between Bs and Ms "
              f"(reference bath, time from {hi:g} to {lo:g} C: {d30['centre_in_bainite_range_s']:.0f} s at the "
              f"30 mm centre, {ref40['centre_in_bainite_range_s']:.0f} s at the 40 mm centre, "
              f"{ref40['under_surface_in_bainite_range_s']:.0f} s 1 mm under its surface). This is the same "
              "over-prediction the SUJ2 page keeps open (`ttt_to_cct_max_bainite`), here much larger because a "
              "quenched bar cools far more slowly below 450 C than a linear-rate dilatometer run. In the core the "
              "pearlite law (set by Kawulok's 12 C/s critical rate) leaves the 30 mm centre almost pearlite-free at "
              "its t8/5; the card's 58 HRC there needs pearlite, so either the card's oil was slower than the "
              "library's accelerated oil or its heat was less hardenable than Kawulok's. The slowest bracket member "
              "(the reference oil) reaches the 40 mm core value only with "
              f"{d40['reference_oil_still_60C']['phases']['centre']['pearlite']:.0%} pearlite, and its surface is "
              "then far too soft. Nothing was tuned to these data: the missed targets stay open with this reason."]
    c = m["checks"]
    lines += ["", f"Checks on the {CHECK_ROUND_MM:g} mm round: element sizes halved change the mid-length traverse "
              f"by at most {c['mesh_max_difference_HRC']:.2f} HRC; a {LENGTH_CHECK_PER_DIAMETER:g} x D bar instead "
              f"of {LENGTH_PER_DIAMETER:g} x D by at most {c['length_max_difference_HRC']:.2f} HRC.", "",
              "![traverses](SUJ2_rounds_traverses.png)"]
    return "\n".join(lines)
