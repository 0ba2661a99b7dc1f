"""Validation page of the ball-bearing run-out / NRRO models (reference sec. 2 and 3).

``write(reports_dir)`` regenerates reports/bearing_runout.md and its PNGs from the library:
the published frequency tables re-derived one waviness at a time, the linear limit of the Hertz
model, the benchmark of the all-first-order-waviness case, and the studies (frequency maps for
Z = 3..20, ball diameter differences, wavy balls with phases, unequal ball spacing vs load).
"""

from __future__ import annotations

import copy
import math
import pathlib
import platform
import time
from typing import Any

import matplotlib.pyplot as plt
import numpy as np

from quenchsim.bearings.runout import parse_case, studies
from quenchsim.bearings.runout import run as runout_run
from quenchsim.bearings.runout.analysis import analyse, simulate, spectra_and_peaks
from quenchsim.bearings.runout.linear2d import series_spring_N_m
from quenchsim.bearings.runout.plots import orbit_plot, spectrum_plot
from quenchsim.validation import page_written_by, written_page

TITLE = "Ball-bearing run-out / NRRO (quasi-static 2-D linear-spring and 3-D Hertz models)"
SLOW = False

PAGE = "bearing_runout.md"
CASES = pathlib.Path(__file__).resolve().parents[3] / "cases"
BENCH_CASE = CASES / "runout_hdd_first_order.toml"
BENCH_REPEATS = 7
AMP_UM = 0.01  # single-waviness amplitude of the table runs (p-p)


def _fmt(x: float, digits: int = 4) -> str:
    return f"{x:.{digits}g}"


def _case(base: dict[str, Any], model: str, **extra: Any):
    data = copy.deepcopy(base)
    data["model"] = model
    data.update(extra)
    return parse_case(data)


def _find(peaks, direction: str, freq: float, tol: float):
    hits = [p for p in peaks if p.direction == direction and abs(abs(p.frequency_hz) - freq) < tol]
    return hits[0] if hits else None


def _others(peaks, keep: list, rel: float = 0.01) -> int:
    """Lines above rel x the strongest that are not among `keep` (x and y lines mirror the whirl)."""
    if not peaks:
        return 0
    top = max(p.amplitude_pp_m for p in peaks)
    kept = {(p.direction, round(abs(p.frequency_hz), 6)) for p in keep if p is not None}
    return sum(1 for p in peaks if p.amplitude_pp_m > rel * top and p.direction in ("radial", "axial")
               and (p.direction, round(abs(p.frequency_hz), 6)) not in kept)


def _line_hz(f, fr: float, rel_hz: float, coeffs: tuple[int, int, int, int]) -> float:
    """a f_rel + b f_r + c f_c + d f_b for coeffs (a, b, c, d)."""
    a, b, c, d = coeffs
    return a * rel_hz + b * fr + c * f.cage_hz + d * f.ball_spin_hz


def _row_runs(model: str, base: dict[str, Any], extra: dict[str, Any]):
    case = _case(base, model, **extra)
    _, peaks, f = spectra_and_peaks(case, simulate(case))
    return case, peaks, f


def _table_2d() -> list[str]:
    """The sec. 2 table, n = 1, 2: (imperfection, order, direction, label, (a, b, c, d) of
    a f_i + b f_r + c f_c + d f_b per line, published amplitude ratio)."""
    z, cot = 8, 1.0 / math.tan(math.radians(19.8))
    rows = []
    for n in (1, 2):
        nz = n * z
        rows += [("inner raceway", "inner", nz - 1, "radial", f"{nz} f_i - f_r", [(nz, -1, 0, 0)], 1.0),
                 ("inner raceway", "inner", nz + 1, "radial", f"{nz} f_i + f_r", [(nz, 1, 0, 0)], 1.0),
                 ("inner raceway", "inner", nz, "axial", f"{nz} f_i", [(nz, 0, 0, 0)], cot),
                 ("outer raceway", "outer", nz - 1, "radial", f"{nz} f_c", [(0, 0, nz, 0)], 1.0),
                 ("outer raceway", "outer", nz + 1, "radial", f"{nz} f_c", [(0, 0, nz, 0)], 1.0),
                 ("outer raceway", "outer", nz, "axial", f"{nz} f_c", [(0, 0, nz, 0)], cot)]
    rows += [("ball diameter (one ball)", None, "-", "radial", "f_c", [(0, 0, 1, 0)], 4 / z),
             ("ball diameter (one ball)", None, "-", "axial", "none", [], None)]
    for n in (1, 2):
        rows += [("ball waviness (one ball)", "ball", 2 * n, "radial", f"{2 * n} f_b -+ f_c",
                  [(0, 0, -1, 2 * n), (0, 0, 1, 2 * n)], 4 / z),
                 ("ball waviness (one ball)", "ball", 2 * n, "axial", f"{2 * n} f_b", [(0, 0, 0, 2 * n)], 2 / z * cot)]
    lines = ["| imperfection | order | direction | predicted | f predicted [Hz] | f found [Hz] | found as | "
             "ratio published | ratio found | other lines > 1 % |", "|---|---|---|---|---|---|---|---|---|---|"]
    tally = METRICS.setdefault("table2d", {"missing_lines": 0, "unlisted_lines": 0, "max_ratio_rel_error": 0.0})
    for name, part, order, direction, formula, coeffs, ratio in rows:
        if part is None:
            extra = {"ball_diameter_deviation": [{"ball": 0, "deviation_um": AMP_UM}]}
        else:
            extra = {"waviness": [{"part": part, "order": order, "amplitude_um_pp": AMP_UM,
                                   **({"ball": 0} if part == "ball" else {})}]}
        case, peaks, f = _row_runs("linear2d", studies.BEARING_695, extra)
        tol = 0.3 / case.duration_s
        targets = [_line_hz(f, case.speed_hz, f.inner_rel_cage_hz, c) for c in coeffs]
        found = [_find(peaks, direction, t, tol) for t in targets]
        # lines the table lists for this imperfection in any direction (the sibling rows)
        listed = [_find(peaks, d, _line_hz(f, case.speed_hz, f.inner_rel_cage_hz, c), tol)
                  for nm, pt, od, d, _, cs, _ in rows if (nm, pt, od) == (name, part, order) for c in cs]
        if not coeffs:
            absent = not [p for p in peaks if p.direction == direction]
            tally["missing_lines"] += 0 if absent else 1   # a line where the table says none
            lines.append(f"| {name} | {order} | {direction} | none | - | {'none' if absent else 'FOUND'} | - | - | - | - |")
            continue
        ok = all(p is not None for p in found)
        ratio_found = sum(p.amplitude_pp_m for p in found) / (AMP_UM * 1e-6) if ok else float("nan")
        others = _others(peaks, listed)
        tally["missing_lines"] += sum(p is None for p in found)
        tally["unlisted_lines"] += others
        tally["max_ratio_rel_error"] = max(tally["max_ratio_rel_error"],
                                           abs(ratio_found / ratio - 1.0) if ok else math.inf)
        lines.append(
            f"| {name} | {order} | {direction} | {formula} | {', '.join(f'{t:.3f}' for t in targets)} | "
            f"{', '.join('MISSING' if p is None else f'{abs(p.frequency_hz):.3f}' for p in found)} | "
            f"{', '.join('-' if p is None else p.source + (f' ({p.whirl})' if p.whirl else '') for p in found)} | "
            f"{_fmt(ratio)}{' (sum)' if len(coeffs) > 1 else ''} | {_fmt(ratio_found)} | {others} |")
    return lines


def _table_3d() -> list[str]:
    """The sec. 3 first-order table, n = 1, 2: lines in (x, y) and z as (a, b, c, d) of
    a f_o + b f_r + c f_c + d f_b (f_o per ball; the table's ball-pass n f_i = nZ f_c, n f_o = nZ f_o)."""
    z = 8
    lines = ["| waviness on | order | published x, y | published z | x, y found [Hz] (as) | z found [Hz] (as) | "
             "other lines > 1 % |", "|---|---|---|---|---|---|---|"]
    tally = METRICS.setdefault("table3d", {"missing_lines": 0, "unlisted_lines": 0})
    for n in (1, 2):
        nz = n * z
        specs = [("inner", nz, "-", f"{n} f_i", [], [(0, 0, nz, 0)]),
                 ("inner", nz - 1, f"{n} f_i", "-", [(0, 0, nz, 0)], []),
                 ("inner", nz + 1, f"{n} f_i", "-", [(0, 0, nz, 0)], []),
                 ("outer", nz, "-", f"{n} f_o", [], [(nz, 0, 0, 0)]),
                 ("outer", nz + 1, f"{n} f_o + f_r", "-", [(nz, 1, 0, 0)], []),
                 ("outer", nz - 1, f"{n} f_o - f_r", "-", [(nz, -1, 0, 0)], []),
                 ("ball", 2 * n, f"{2 * n} f_o -+ f_c (see note)", f"{2 * n} f_o (see note)",
                  [(0, 0, -1, 2 * n), (0, 0, 1, 2 * n)], [(0, 0, 0, 2 * n)])]
        for part, order, pub_r, pub_z, radial, axial in specs:
            w = {"part": part, "order": order, "amplitude_um_pp": AMP_UM, **({"ball": 0} if part == "ball" else {})}
            case, peaks, f = _row_runs("hertz3d", studies.STANDARD_3D, {"waviness": [w]})
            tol = 0.3 / case.duration_s
            rel = f.outer_rel_cage_hz
            found_r = [_find(peaks, "x", _line_hz(f, case.speed_hz, rel, c), tol) for c in radial]
            found_z = [_find(peaks, "axial", _line_hz(f, case.speed_hz, rel, c), tol) for c in axial]
            keep = found_z + [_find(peaks, "radial", _line_hz(f, case.speed_hz, rel, c), tol) for c in radial]

            def show(found):
                if not found:
                    return "none"
                return ", ".join("MISSING" if p is None else f"{abs(p.frequency_hz):.2f} ({p.source})" for p in found)

            others = _others(peaks, keep)
            tally["missing_lines"] += sum(p is None for p in found_r + found_z)
            tally["unlisted_lines"] += others
            lines.append(f"| {part} | {order} | {pub_r} | {pub_z} | {show(found_r)} | {show(found_z)} | "
                         f"{others} |")
    return lines


def _linear_limit() -> tuple[list[str], float, list[tuple[float, float]]]:
    base = studies.STANDARD_3D
    amps = [0.005, 0.01, 0.02, 0.05, 0.1, 0.2]
    lines = ["| amplitude [um p-p] | 3-D / 2-D - 1, line n f_i | 3-D / 2-D - 1, line n f_o - f_r | "
             "2nd-order line (inner 4 lobes, z at 8 f_c) [nm p-p] | 3-D radial NRRO [nm] | 2-D radial NRRO [nm] |",
             "|---|---|---|---|---|---|"]
    second, excess = [], []
    for a in amps:
        w = [{"part": "inner", "order": 9, "amplitude_um_pp": a}, {"part": "outer", "order": 7, "amplitude_um_pp": a},
             {"part": "inner", "order": 4, "amplitude_um_pp": a}, {"part": "outer", "order": 3, "amplitude_um_pp": a}]
        res = {}
        for model in ("hertz3d", "linear2d"):
            r = runout_run(_case(base, model, waviness=w))
            tol = 0.3 / r.case.duration_s
            f = r.frequencies
            l1 = _find(r.peaks, "radial", f.ball_pass_inner_hz, tol)
            l2 = _find(r.peaks, "radial", f.ball_pass_outer_hz - r.case.speed_hz, tol)
            res[model] = (l1.amplitude_pp_m, l2.amplitude_pp_m, r.nrro_pp_m["radial"])
        case = _case(base, "hertz3d", waviness=[{"part": "inner", "order": 4, "amplitude_um_pp": a}])
        _, peaks, f = spectra_and_peaks(case, simulate(case))
        s2 = _find(peaks, "axial", f.ball_pass_inner_hz, 0.3 / case.duration_s)
        second.append(s2.amplitude_pp_m)
        h, lin = res["hertz3d"], res["linear2d"]
        excess.append((a, 100.0 * (h[2] / lin[2] - 1.0)))
        lines.append(f"| {a} | {h[0] / lin[0] - 1:.2e} | {h[1] / lin[1] - 1:.2e} | {s2.amplitude_pp_m * 1e9:.4g} | "
                     f"{h[2] * 1e9:.4g} | {lin[2] * 1e9:.4g} |")
    slope = float(np.polyfit(np.log(amps), np.log(second), 1)[0])
    return lines, slope, excess


def _benchmark(reports_dir: pathlib.Path) -> tuple[list[str], list[pathlib.Path]]:
    from quenchsim.bearings.runout import load_case

    case = load_case(BENCH_CASE)
    simulate(case)  # warm-up (imports, caches)
    solve_times, total_times = [], []
    for _ in range(BENCH_REPEATS):
        t0 = time.perf_counter()
        tr = simulate(case)
        t1 = time.perf_counter()
        result = analyse(case, tr, t1 - t0)
        t2 = time.perf_counter()
        solve_times.append(t1 - t0)
        total_times.append(t2 - t0)
    lin = simulate(parse_case({**_toml(BENCH_CASE), "model": "linear2d"}))
    diff = max(np.abs(tr.x_m - lin.x_m).max(), np.abs(tr.y_m - lin.y_m).max())
    METRICS["benchmark"] = {"hertz_vs_linear_max_orbit_diff_m": float(diff)}
    png = [orbit_plot(result, reports_dir / "runout_bench_orbit.png", "all first-order waviness, Z = 8, 3-D Hertz"),
           spectrum_plot(result, reports_dir / "runout_bench_spectrum.png",
                         "all first-order waviness, Z = 8, 5400 rpm, 4096 points", label_peaks=10)]
    peaks = sorted((p for p in result.peaks if p.direction in ("radial", "axial")), key=lambda p: -p.amplitude_pp_m)
    lines = [f"Case `cases/{BENCH_CASE.name}`: {case.samples} time steps, {case.balls} balls, "
             f"contact angle {math.degrees(case.contact_angle_rad):.2f} deg (from 10 um clearance at 20 N), "
             f"Newton iterations {tr.iterations} (all steps at once).", "",
             "| quantity | value |", "|---|---|",
             f"| solve (excitation + batched Newton), median of {BENCH_REPEATS} [s] | {np.median(solve_times):.4f} |",
             f"| solve + spectra + peak identification + NRRO, median [s] | {np.median(total_times):.4f} |",
             f"| min / max solve [s] | {min(solve_times):.4f} / {max(solve_times):.4f} |",
             "| paper (850 MHz PC) [s] | ~5 |",
             *(f"| {d} run-out / NRRO [nm p-p] | {result.runout_pp_m[d] * 1e9:.2f} / {result.nrro_pp_m[d] * 1e9:.2f} |"
               for d in ("radial", "axial")),
             f"| max orbit difference Hertz vs linear model [m] | {diff:.2e} |",
             f"| machine | {platform.machine()}, Python {platform.python_version()}, numpy {np.__version__} |",
             "", "Lines (whirl 'radial' and 'axial'):", "",
             "| direction | f [Hz] | f / f_r | amplitude [nm p-p] | source |", "|---|---|---|---|---|"]
    lines += [f"| {p.direction}{' (' + p.whirl + ')' if p.whirl else ''} | {p.frequency_hz:.2f} | {p.order_per_rev:.4f} | "
              f"{p.amplitude_pp_m * 1e9:.3f} | {p.source} |" for p in peaks]
    return lines, png


def _toml(path: pathlib.Path) -> dict[str, Any]:
    import tomllib

    return tomllib.loads(path.read_text(encoding="utf-8"))


def _frequency_maps(reports_dir: pathlib.Path) -> tuple[list[str], list[pathlib.Path]]:
    base = copy.deepcopy(studies.BEARING_695)
    base["bearing"].update(pitch_diameter_mm=7.0, ball_diameter_mm=1.0)
    base["operation"].pop("step_deg")
    base["operation"].update(revolutions=8, samples=2048)
    records = studies.frequency_map(base, range(3, 21), range(1, 21))
    fig, axes = plt.subplots(1, 3, figsize=(15, 5.2), sharey=True)
    for ax, part in zip(axes, ("inner", "outer", "ball")):
        for direction, colour, dx in (("radial", "tab:blue", -0.15), ("axial", "tab:red", 0.15)):
            rs = [r for r in records if r.part == part and r.direction == direction]
            if rs:
                ax.scatter([r.order + dx for r in rs], [r.balls for r in rs],
                           s=[60 * min(r.amplitude_ratio, 3.0) + 4 for r in rs], c=colour, alpha=0.6, label=direction)
        ax.set_title(f"{part} waviness (inner ring rotating)")
        ax.set_xlabel("waviness order")
        ax.set_xticks(range(1, 21))
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("number of balls Z")
    axes[0].set_yticks(range(3, 21))
    axes[0].legend(loc="upper left")
    fig.suptitle("Lines excited by one waviness (linear model, bubble area ~ amplitude ratio)")
    fig.tight_layout()
    png = reports_dir / "runout_frequency_map.png"
    fig.savefig(png, dpi=100)
    plt.close(fig)
    lines = ["| order | inner: radial | inner: axial | outer: radial | outer: axial | ball: radial | ball: axial |",
             "|---|---|---|---|---|---|---|"]
    for order in range(1, 21):
        cells = []
        for part in ("inner", "outer", "ball"):
            for direction in ("radial", "axial"):
                rs = [r for r in records if r.balls == 8 and r.part == part and r.order == order and r.direction == direction]
                cells.append(", ".join(f"{r.source} ({r.amplitude_ratio:.3g})" for r in rs) or "-")
        lines.append(f"| {order} | " + " | ".join(cells) + " |")
    return lines, [png]


def _nonlinear_map(reports_dir: pathlib.Path) -> tuple[list[str], list[pathlib.Path]]:
    """3-D Hertz model, Z = 8, outer rotating, 0.1 um p-p of one order at a time on each ring."""
    base = copy.deepcopy(studies.STANDARD_3D)
    # 128 points per revolution: third-order lines of order 20 (60 f_c ~ 34 f_r) stay below Nyquist
    base["operation"].update(revolutions=16, samples=2048)
    amp = 0.1
    records = studies.frequency_map(base, range(8, 9), range(1, 21), parts=("inner", "outer"), model="hertz3d",
                                    amplitude_um_pp=amp)
    fig, axes = plt.subplots(1, 2, figsize=(13, 5), sharey=True)
    for ax, part in zip(axes, ("inner", "outer")):
        for direction, colour in (("radial", "tab:blue"), ("axial", "tab:red")):
            rs = [r for r in records if r.part == part and r.direction == direction]
            if rs:
                ax.scatter([r.order for r in rs], [abs(r.order_per_rev) for r in rs],
                           s=[12 * max(np.log10(r.amplitude_ratio) + 5, 0.3) ** 2 for r in rs], c=colour, alpha=0.55,
                           label=direction)
        ax.set_title(f"{part} waviness {amp} um p-p, 3-D Hertz, Z = 8, outer rotating")
        ax.set_xlabel("waviness order")
        ax.set_xticks(range(1, 21))
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("|line frequency| / f_r")
    axes[0].legend()
    fig.tight_layout()
    png = reports_dir / "runout_nonlinear_map.png"
    fig.savefig(png, dpi=100)
    plt.close(fig)
    lines = ["| part | order | direction | f / f_r | amplitude ratio | source |", "|---|---|---|---|---|---|"]
    for r in records:
        if r.order % 8 not in (0, 1, 7):
            lines.append(f"| {r.part} | {r.order} | {r.direction} | {abs(r.order_per_rev):.4f} | {r.amplitude_ratio:.3g} | "
                         f"{r.source} |")
    return lines, [png]


def _diameter_table() -> list[str]:
    rows = studies.diameter_difference_study(studies.BEARING_695, 0.1)
    lines = ["| larger balls | placement | ball indices | linear closed form [um] | 2-D linear [um] | 3-D Hertz [um] |",
             "|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['balls_larger']} | {r['placement']} | {r['balls']} | {r['linear_closed_form_um']:.4f} | "
                     f"{r['linear2d_radial_um']:.4f} | {r['hertz3d_radial_um']:.4f} |")
    return lines


def _wavy_table() -> list[str]:
    lines = ["| model | phase pattern | radial run-out [um] | axial run-out [um] | 2 f_b axial [um] | 2 f_b - f_c [um] | "
             "2 f_b + f_c [um] | phasor sums (axial, -, +) |", "|---|---|---|---|---|---|---|---|"]
    for model in ("linear2d", "hertz3d"):
        for r in studies.wavy_balls_study(studies.BEARING_695, 2, 0.1, model=model):
            lines.append(f"| {model} | {r['pattern']} | {r['radial_runout_um']:.4f} | {r['axial_runout_um']:.4f} | "
                         f"{r['axial_kfb_um']:.4f} | {r['radial_kfb_minus_fc_um']:.4f} | {r['radial_kfb_plus_fc_um']:.4f} | "
                         f"{r['sum_axial']:.2f}, {r['sum_minus']:.2f}, {r['sum_plus']:.2f} |")
    return lines


def _spacing(reports_dir: pathlib.Path) -> tuple[list[str], list[pathlib.Path], float]:
    base = copy.deepcopy(studies.BEARING_695)
    k_ref = 2.0 * series_spring_N_m(parse_case({**copy.deepcopy(base), "model": "linear2d"}))
    base["bearing"]["ball_spring_N_per_m"] = k_ref
    loads = np.geomspace(1.0, 64.0, 7)
    arrangements = {"8 balls, one displaced 2 deg": (8, [2.0] + [0.0] * 7),
                    "7 balls in an 8-pocket crown cage": (7, studies.crown_cage_errors(8, 7))}
    rows = studies.spacing_study(base, loads, arrangements)
    fig, ax = plt.subplots(figsize=(7.5, 5))
    for name, style in zip(arrangements, ("o-", "s-")):
        rs = [r for r in rows if r["arrangement"] == name]
        for model, colour in (("linear2d", "tab:blue"), ("hertz3d", "tab:red")):
            ax.loglog([r["axial_load_N"] for r in rs], [r[f"{model}_radial_um"] * 1e3 for r in rs], style, color=colour,
                      label=f"{name}, {model}", ms=4)
    ax.set_xlabel("axial load [N]")
    ax.set_ylabel("radial run-out [nm p-p]")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    ax.set_title("Unequal ball spacing, 695 bearing (linear k fixed at its 7.8 N Hertz value)")
    fig.tight_layout()
    png = reports_dir / "runout_spacing_vs_load.png"
    fig.savefig(png, dpi=100)
    plt.close(fig)
    lines = ["| arrangement | axial load [N] | 2-D linear [nm] | 3-D Hertz [nm] |", "|---|---|---|---|"]
    lines += [f"| {r['arrangement']} | {r['axial_load_N']:.3g} | {r['linear2d_radial_um'] * 1e3:.4g} | "
              f"{r['hertz3d_radial_um'] * 1e3:.4g} |" for r in rows]
    return lines, [png], k_ref


def _write(reports_dir: pathlib.Path) -> list[pathlib.Path]:
    """Regenerate reports_dir/bearing_runout.md and its PNGs."""
    reports_dir = pathlib.Path(reports_dir)
    reports_dir.mkdir(parents=True, exist_ok=True)
    t_start = time.process_time()
    bench, bench_png = _benchmark(reports_dir)
    table2d = _table_2d()
    table3d = _table_3d()
    limit, slope, excess = _linear_limit()
    fmap, fmap_png = _frequency_maps(reports_dir)
    nmap, nmap_png = _nonlinear_map(reports_dir)
    diam = _diameter_table()
    wavy = _wavy_table()
    spacing, spacing_png, k_ref = _spacing(reports_dir)
    std = parse_case({**copy.deepcopy(studies.STANDARD_3D), "model": "hertz3d"})
    fk = runout_run(std).frequencies
    kin = {"8fc": 8 * fk.cage_hz, "8fo+fr": fk.ball_pass_outer_hz + std.speed_hz, "bin": 1.0 / std.duration_s,
           "2fb": 2 * fk.ball_spin_hz, "2fo": 2 * fk.ball_pass_outer_hz,
           "diff_pct": 100.0 * (fk.ball_pass_outer_hz / fk.ball_spin_hz - 1.0),
           "diff_bins": 2 * (fk.ball_pass_outer_hz - fk.ball_spin_hz) * std.duration_s}
    text = f"""# Ball-bearing run-out / NRRO (quasi-static 2-D linear-spring and 3-D Hertz models)

CPU {{cpu:.0f}} s. Models, inputs and
assumptions: reference sec. 2 (2-D linear springs, inner ring rotating) and sec. 3 (3-D, Hertz,
fixed contact angle, outer ring rotating). Library: `quenchsim/bearings/runout/`; CLI:
`quenchsim bearings runout CASE.toml --json`; example cases `cases/runout_*.toml`.

Conventions: amplitudes are peak-to-peak (2 x the Hann-windowed single-sided spectral amplitude,
refined by two-bin Hann interpolation); "radial" is the whirl spectrum of x + i y (sign =
forward/backward with respect to the rotating ring), "axial" is z. Kinematic labels: f_r
rotating-ring speed, f_c cage, f_b ball spin relative to the cage, f_i = f_r - f_c (inner
rotating) or f_o = f_r - f_c (outer rotating) per ball; the 3-D reference's n f_i, n f_o are
ball-pass frequencies, i.e. nZ f_c and nZ f_o in these labels.

Targets and roles: no printed number fixes an input here (the bearings' dimensions are the papers' Tables,
the waviness amplitudes chosen small). The targets are the references' tables of which waviness excites which
line with which amplitude ratio -- kinematic results of the same quasi-static model: verification. The papers'
measured spectra are not printed, so nothing on this page is a validation.

## 1. Benchmark: all first-order waviness (Z = 8; Z-1, Z, Z+1 lobes on both rings, 20 nm each; 5400 rpm; 4096 points)

All time steps are solved together: one batched 3 x 3 Newton system per step, vectorised over
steps and balls, warm-started from the rigid preload solution. With Z equally spaced balls, orders
Z-1, Z, Z+1 alias (at the balls) to a rigid shift plus a uniform approach, so every ball carries
the same load at every step and the Hertz orbit equals the linear one to rounding (last row) --
a property of this case, not of the model (section 4 shows the nonlinear terms).

{chr(10).join(bench)}

![orbit](runout_bench_orbit.png)
![spectrum](runout_bench_spectrum.png)

Note the near-coincidence 8 f_c = {kin['8fc']:.2f} Hz vs 8 f_o + f_r = {kin['8fo+fr']:.2f} Hz for this
bearing (16 f_c ~ 9 f_r when D cos(alpha)/d_m ~ 1/8): inner Z +- 1 and outer Z + 1 lines fall into
the same FFT bin ({kin['bin']:.2f} Hz) of the 0.8 s record.

## 2. The 2-D table (reference sec. 2; 695 bearing, inner ring rotating, linear model)

One imperfection of {AMP_UM} um p-p (or one ball {AMP_UM} um larger) at a time; 10 revolutions,
1 deg steps. "ratio" = line p-p / imperfection p-p (published ratios: raceway radial 1, axial
cot(alpha); one ball 4/Z radial (sum of both sidebands for waviness), (2/Z) cot(alpha) axial).
"other lines" counts radial/axial lines above 1 % of the strongest that the table does not list.
Tests: `tests/bearings/test_runout_linear2d.py`, and the order rule for every Z = 3..20, order
1..20 in `tests/bearings/test_runout_studies.py`.

{chr(10).join(table2d)}

The 2-D model places every form error in the radial plane (the published ratios 4/Z and
(2/Z) cot(alpha) for balls follow from that); the 3-D model puts a ball's diameter error along
the contact line, so its ball lines are 1/cos(alpha) (radial) and 1/(cos(alpha) cot(alpha))
(axial) times the 2-D values.

## 3. The 3-D first-order table (reference sec. 3; standard model, outer ring rotating, Hertz model)

One waviness of {AMP_UM} um p-p at a time, 72 revolutions, 4096 points. Tests:
`tests/bearings/test_runout_hertz3d.py`.

{chr(10).join(table3d)}

Note on the ball row: the reference prints 2n f_o -+ f_c (x, y) and 2n f_o (z). A ball of
waviness order 2n changes its diameter at 2n f_b, and the lines found are at 2n f_b -+ f_c and
2n f_b, as the reference's own sec. 2 table states for this mechanism (and as an independent NRRO
analysis of HDD spindle bearings reports: dominant radial lines f_c and 2 f_b +- f_c, axial 2 f_b;
Y. C. Kim, S. K. Choi, K. C. Yoon, "NRRO analysis of HDD spindle ball bearings using the measured
geometric imperfection", 2002, https://koreascience.kr/article/CFKO200225121648695.page).
For this bearing 2 f_b = {kin['2fb']:.1f} Hz and 2 f_o = {kin['2fo']:.1f} Hz (ball-pass) differ by
{kin['diff_pct']:.1f} %, {kin['diff_bins']:.0f} FFT bins, so they are not the same line; we read the printed
f_o in that row as a symbol slip and test against 2n f_b.

## 4. Linear limit and second-order terms (3-D vs 2-D, standard model, outer rotating)

Inner 9 + outer 7 lobes (first-order lines n f_i and n f_o - f_r) plus inner 4 + outer 3 lobes
(no first-order line, but unequal ball loads), all at the same amplitude. The first-order lines
of the 3-D model equal the linear model's (columns 2-3; second-order products of these orders do
not fall on the first-order frequencies), while the total radial NRRO of the 3-D model exceeds the
linear one by its nonlinear lines, a difference that grows with the amplitude (last two columns:
{excess[0][1]:.2g} % at {excess[0][0]} um, {excess[-1][1]:.2g} % at {excess[-1][0]} um). Inner 4 lobes alone
(= Z/2: j = 2 of the reference's W = nZ/j) gives an axial line at 8 f_c only through the Hertz nonlinearity; fitted log-log slope of its
amplitude against the waviness amplitude: **{slope:.4f}** (2 = grows with amplitude squared).

{chr(10).join(limit)}

Nonlinear (higher-order) lines of the 3-D model, one waviness order 1..20 at a time at 0.1 um
p-p, Z = 8 (orders other than nZ, nZ +- 1 only; amplitude ratio = line / waviness, both p-p):

{chr(10).join(nmap)}

![nonlinear map](runout_nonlinear_map.png)

## 5. Which lines each waviness order excites, Z = 3..20, orders 1..20 (linear model, inner rotating)

Bearing: pitch 7 mm, balls 1 mm, contact angle 19.8 deg, so that up to 20 balls fit. Bubble
area ~ amplitude ratio.

![frequency map](runout_frequency_map.png)

Z = 8 (line label, amplitude ratio):

{chr(10).join(fmap)}

## 6. Ball diameter differences: adjacent vs spread (695, 0.1 um larger balls, maximum radial run-out p-p)

Linear closed form: the orbit is a circle of diameter (4/Z) dD |sum_j exp(i theta_j)| over the
larger balls; two opposite (or four alternate) balls cancel, adjacent balls add.

{chr(10).join(diam)}

## 7. All balls wavy (order 2, 0.1 um p-p each) with phase differences (695)

The balls' lines add as phasors: axial 2 f_b with |sum exp(i phi_j)|, the sidebands 2 f_b - f_c
and 2 f_b + f_c with |sum exp(i(phi_j + theta_j))| and |sum exp(i(phi_j - theta_j))|. Equal phases
cancel all radial run-out but add the axial; a phase step of 360/Z moves everything into one
radial sideband; 720/Z cancels all three lines.

{chr(10).join(wavy)}

## 8. Unequal ball spacing vs axial load (695)

One ball displaced 2 deg along the pitch circle, and 7 balls in an 8-pocket crown cage. The
linear model uses a fixed spring k = {k_ref:.4g} N/m per contact (its Hertz value at 7.8 N):
run-out proportional to the axial load. The Hertz model's run-out follows the preload approach,
~ F^(2/3), and the contact-angle is kept fixed as in sec. 3.

![spacing](runout_spacing_vs_load.png)

{chr(10).join(spacing)}
"""
    path = reports_dir / PAGE
    path.write_text(text.replace("{cpu:.0f}", f"{time.process_time() - t_start:.0f}"), encoding="utf-8")
    return [path, *bench_png, *fmap_png, *nmap_png, *spacing_png]


METRICS: dict = {}
"""Named metrics the page code records while it runs (the targets' metrics)."""


def run(workdir: pathlib.Path) -> dict:
    """Run the study: the page code writes its page and PNGs into ``workdir``; the page becomes the body."""
    return page_written_by(_write, METRICS, workdir)


page = written_page
