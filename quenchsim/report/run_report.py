"""The report of run and sweep directories: one self-contained HTML file (PNGs embedded as base64)
plus the same content as Markdown with the PNGs in a sibling folder.

For a run directory: cooling curves at the probes, phase and hardness maps of the final state,
the hardness-depth traverse, the distortion x10 over the pre-quench outline, the residual hoop-stress
traverse, and the dimension table against the case's ``[measured]`` table. Whatever a run directory
lacks is listed under "Not in this run directory". For a sweep directory (``quenchsim sweep``
output): the results table and response plots of the key outputs against each swept input.
"""

from __future__ import annotations

import base64
import datetime
import html
import json
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from quenchsim.errors import InputError
from quenchsim.report import report_plots as plots
from quenchsim.report.lengths import is_length, mm
from quenchsim.report.report_data import PHASES, is_sweep_dir, measured_dimensions
from quenchsim.results import RunResults, files, load

RESPONSE_OUTPUTS = ("hardness.depth_mm.", "hardness.core_HRC", "hardness.surface_HRC.", "dimensions_mm.change.",
                    "shape_mm.change.bore_crown", "shape_mm.change.od_crown", "shape_mm.change.bore_taper",
                    "shape_mm.change.od_taper", "shape_mm.change.top_face_dish",
                    "residual_stress_MPa.hoop.", "phases_final.martensite.mean", "phases_final.bainite.mean",
                    "phases_final.austenite.mean", "probes.*.t8_5_s", "probes.*.t_to_300C_s", "solver.wall_time_s")
"""Result columns plotted against the swept inputs, in this order (``*`` matches a probe name)."""
MAX_RESPONSES = 12


@dataclass
class Item:
    """One piece of a section: an image (PNG bytes), a table (header, rows), a paragraph or a missing item."""

    kind: str
    title: str
    image: bytes = b""
    header: list[str] = field(default_factory=list)
    rows: list[list[Any]] = field(default_factory=list)
    text: str = ""


@dataclass
class Section:
    title: str
    items: list[Item]

    @property
    def anchor(self) -> str:
        return re.sub(r"[^a-z0-9]+", "-", self.title.lower()).strip("-")


def fmt(value: Any) -> str:
    """A table cell: 4 significant digits for floats, a dash for missing values."""
    if value is None or (isinstance(value, float) and not np.isfinite(value)):
        return "-"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, float):
        return f"{value:.4g}"
    return str(value)


# -- run directory --------------------------------------------------------------------------------------
def _maps(run: RunResults, missing: list[str]) -> list[Item]:
    frame = run.frame
    if frame is None:
        missing.append("phase and hardness maps: no results_*.vtu frame")
        return []
    items = []
    phases = [p for p in PHASES if p in frame.point_data]
    labels = {"austenite": "retained austenite", "pearlite": "pearlite", "bainite": "bainite",
              "martensite": "martensite"}
    if phases:
        items.append(Item("image", "Phase fractions, final state",
                          image=plots.field_maps(frame, [(p, labels[p], "viridis", 0.0, 1.0) for p in phases],
                                                 f"Phase fractions, final state ({frame.path.name}): {run.title}")))
    else:
        missing.append(f"phase maps: {frame.path.name} has no phase fractions")
    hard = [(n, label, "inferno", None, None) for n, label in (("hardness_HRC", "hardness (HRC)"),
                                                              ("hardness_HV", "hardness (HV)"))
            if n in frame.point_data]
    if hard:
        items.append(Item("image", "Hardness map, final state",
                          image=plots.field_maps(frame, hard, f"Hardness, final state: {run.title}")))
    else:
        missing.append(f"hardness map: {frame.path.name} has no hardness_HRC / hardness_HV")
    stress = [(n, label, "coolwarm", None, None) for n, label in
              (("stress_tt_Pa", "hoop stress (Pa)"), ("stress_zz_Pa", "axial stress (Pa)"),
               ("von_mises_Pa", "von Mises (Pa)"), ("equivalent_plastic_strain", "equiv. plastic strain"))
              if n in frame.point_data]
    if stress:
        items.append(Item("image", "Residual stress maps, final state",
                          image=plots.field_maps(frame, stress, f"Residual stress, final state: {run.title}")))
    return items


def _summary_tables(run: RunResults) -> list[Item]:
    s = run.summary or {}
    items = []
    solver = s.get("solver", {})
    text = f"Status: {files.run_status(run.summary)}."
    if s.get("error"):
        text += f" Error: {s['error']} (stopped at t = {fmt(s.get('stopped_at_s'))} s)."
    if solver:
        text += (f" Solver: {fmt(solver.get('steps'))} steps, {fmt(solver.get('dofs'))} dofs, "
                 f"wall time {fmt(solver.get('wall_time_s'))} s.")
    items.append(Item("text", "Status", text=text))
    warning = files.status_warning(run.summary)
    if warning:
        items.append(Item("text", "Warning", text=f"WARNING: {warning}."))
    views = [name for name in ("results.pvd", "final_3d.vtu") if (run.path / name).is_file()]
    if views:
        items.append(Item("text", "ParaView", text=f"For ParaView: {' and '.join(views)} in {run.path} "
                                                   "(results.pvd: the r-z section over time, x = r, y = z in m; "
                                                   "final_3d.vtu: the final state revolved into a 3-D sector)."))
    probes = s.get("probes", {})
    if probes:
        items.append(Item("table", "Probe cooling times (s)", header=["probe", "to 500 C", "to 300 C", "t8/5"],
                          rows=[[n, p.get("t_to_500C_s"), p.get("t_to_300C_s"), p.get("t8_5_s")]
                                for n, p in probes.items()]))
    hard = s.get("hardness", {})
    if hard:
        through = "through-hardened" if hard.get("through_hardened_mid") else None   # the depth is the wall
        rows = [[f"depth to {fmt(hard.get('threshold_HRC', 58.0))} HRC, {k} (mm)", through or mm(v)]
                for k, v in hard.get("depth_mm", {}).items()]
        rows += [[f"surface HRC, {k}", v] for k, v in hard.get("surface_HRC", {}).items()]
        rows += [["core HRC", hard.get("core_HRC")]]
        items.append(Item("table", "Hardness", header=["quantity", "value"], rows=rows))
    phases = s.get("phases_final", {})
    if phases:
        items.append(Item("table", "Final phase fractions", header=["phase", "min", "mean", "max"],
                          rows=[[p, v.get("min"), v.get("mean"), v.get("max")] for p, v in phases.items()]))
    return items


def _dimension_table(run: RunResults, missing: list[str]) -> list[Item]:
    dims = (run.summary or {}).get("dimensions_mm")
    meas = measured_dimensions(run.case, (run.summary or {}).get("condition"))
    if not dims:
        missing.append("dimension table: summary.json has no dimensions_mm (a run without mechanics)")
        return []
    names = list(dict.fromkeys([*dims.get("before", {}), *meas["before"], *meas["after"]]))
    rows = []
    for k in names:
        sim_change = dims.get("change", {}).get(k)
        meas_change = meas["change"].get(k)
        diff = None if sim_change is None or meas_change is None else sim_change - meas_change
        rows.append([k, *map(mm, (dims.get("before", {}).get(k), dims.get("after", {}).get(k), sim_change,
                                  meas["before"].get(k), meas["after"].get(k), meas_change, diff))])
    header = ["dimension (mm)", "before (sim)", "after (sim)", "change (sim)", "before (measured)",
              "after (measured)", "change (measured)", "change: sim - measured"]
    items = [Item("table", "Dimensions before and after the quench", header=header, rows=rows)]
    warning = files.status_warning(run.summary)
    if warning:
        items.append(Item("text", "Not the finished part", text=f"WARNING: {warning}; the simulated dimensions are "
                                                                 "not comparable with measured ones."))
    if not meas["before"] and not meas["after"]:
        items.append(Item("text", "Measurements", text="The case file carries no [measured] table."))
    else:
        source = (run.case or {}).get("measured", {}).get("source")
        if source:
            items.append(Item("text", "Measurements", text=f"Measured: {source}."))
    items += _shape_table(run)
    budget = (run.summary or {}).get("distortion_budget_mm")
    if budget:
        items.append(Item("image", "Distortion budget: what the dimension change is made of",
                          image=plots.distortion_budget(budget, run.title)))
        parts = list(budget.get("parts", {}))
        keys = list(budget.get("total", {}))
        items.append(Item("table", "Distortion budget (mm; area in mm2)", header=["part", *keys],
                          rows=[[label, *[_budget_cell(k, row.get(k)) for k in keys]] for label, row in (
                              *((plots.BUDGET_LABELS.get(p, p), budget["parts"][p]) for p in parts),
                              ("total (after - before)", budget["total"]),
                              ("sum of parts - total", budget.get("sum_minus_total", {})))]))
        items.append(Item("text", "Budget method", text=budget.get("method", "")))
    else:
        missing.append("distortion budget: summary.json has no distortion_budget_mm (a run without mechanics, or an "
                       "older run)")
    rs = (run.summary or {}).get("residual_stress_MPa")
    if rs:
        locations = list(dict.fromkeys(k for comp in rs.values() for k in comp))
        items.append(Item("table", "Residual stress (MPa)", header=["component", *locations],
                          rows=[[c, *[v.get(k) for k in locations]] for c, v in rs.items()]))
    return items


def _budget_cell(key: str, value: Any) -> Any:
    """A distortion-budget cell: the dimensions in mm to fixed decimals, the section area (mm2) as it is."""
    return value if key.endswith("_mm2") else mm(value)


def _shape_table(run: RunResults) -> list[Item]:
    """The inspector's shape measures (summary.json ``shape_mm``): before, after and change, with the gauge."""
    shape = (run.summary or {}).get("shape_mm")
    if not shape:
        return []
    g = shape["gauge"]
    text = (f"Read on the outline as a gauge would: diameters at {mm(g['heights_before_mm']['bottom'])} / "
            f"{mm(g['heights_before_mm']['mid'])} / {mm(g['heights_before_mm']['top'])} mm above the bottom face "
            f"({mm(g['inset_mm'])} mm, a fraction {fmt(g['inset_fraction'])} of the width, in from each face); taper: "
            "top minus bottom; crown: mid-width minus the mean of the ends (positive: a barrel); straightness: the "
            "largest deviation of the diameter from the line through the ends; face dish: height at the OD side "
            "minus at the bore side. The distortion x10 plot above shows the same outline.")
    return [Item("text", "Shape measures", text=text),
            Item("table", "Shape measures (mm)", header=["measure", "before", "after", "change"],
                 rows=[[k, mm(shape["before"][k]), mm(shape["after"][k]), mm(shape["change"][k])] for k in shape["change"]])]


def _tempered_table(run: RunResults) -> list[Item]:
    """A run with a ``[temper]`` (summary.json ``tempered``): the as-quenched and the tempered state side by side, and
    the tempering part of the distortion budget."""
    s = run.summary or {}
    t = s.get("tempered")
    if not t:
        return []
    rows: list[list[Any]] = []

    def add(label: str, a: Any, b: Any) -> None:
        if isinstance(a, (int, float)) and isinstance(b, (int, float)):
            rows.append([label, a, b, b - a])

    if "hardness" in t:
        add("core HRC", s["hardness"]["core_HRC"], t["hardness"]["core_HRC"])
        for where, v in t["hardness"]["surface_HRC"].items():
            add(f"surface HRC {where}", s["hardness"]["surface_HRC"].get(where), v)
        add("retained austenite (mean)", s["phases_final"]["austenite"]["mean"], t["phases_final"]["austenite"]["mean"])
    if "dimensions_mm" in t:
        for k, v in t["dimensions_mm"]["after"].items():
            add(f"{k} (mm)", s["dimensions_mm"]["after"][k], v)
        for k, v in t["shape_mm"]["after"].items():
            add(f"{k} (mm)", s["shape_mm"]["after"][k], v)
        for comp in ("hoop", "axial"):
            for where, v in t["residual_stress_MPa"][comp].items():
                add(f"{comp} stress {where} (MPa)", s["residual_stress_MPa"][comp][where], v)
    temper = t["temper"]
    items = [Item("table", f"As quenched and tempered ({fmt(temper['temperature_C'])} C, "
                           f"{fmt(temper['time_s'] / 3600.0)} h in the furnace)",
                  header=["quantity", "as quenched", "tempered", "change"], rows=rows)]
    if "tempering_budget_mm" in t:
        items.append(Item("table", "Tempering part of the distortion budget (after the temper minus as quenched, mm)",
                          header=["part", "id", "od", "width"],
                          rows=[[p, v["id"], v["od"], v["width"]] for p, v in t["tempering_budget_mm"].items()]))
    return items


def _uncertainty_table(run: RunResults) -> list[Item]:
    """The bands of ``quenchsim run --uncertainty`` (summary.json ``uncertainty``): every quantity, nominal run
    beside the median and the 5-95 % band of the draws."""
    from quenchsim.sweep import flatten

    block = (run.summary or {}).get("uncertainty")
    if not block:
        return []
    assert run.summary is not None   # it holds the uncertainty block
    nominal = dict(flatten(run.summary))
    rows = [[key, *((mm if is_length(key) else fmt)(v) for v in (nominal.get(key), b["median"], b["p5"], b["p95"]))]
            for key, b in block["quantities"].items()]
    text = (f"{block['runs_ok']} of {block['runs']} full-chain runs with the inputs drawn from the {block['source']}: "
            + ", ".join(f"`{p}`" for p in block["inputs"]) + "."
            + "".join(f" Failed draw {name}: {error}." for name, error in block.get("failures", {}).items()))
    return [Item("text", "Uncertainty", text=text),
            Item("table", "Every summary quantity with its band", header=["quantity", "this run", "median", "5 %", "95 %"],
                 rows=rows)]


def run_section(run: RunResults) -> Section:
    """Everything the report shows of one run directory."""
    items = _summary_tables(run) + _uncertainty_table(run)
    missing: list[str] = []
    if run.probes is not None:
        t = run.probes["time_s"]
        curves = {k[:-2] if k.endswith("_C") else k: v for k, v in run.probes.items() if k != "time_s"}
        items.append(Item("image", "Cooling curves at the probes", image=plots.cooling_curves(t, curves, run.title)))
    else:
        missing.append("cooling curves: no probes.csv with two or more rows")
    items += _maps(run, missing)
    ht = run.hardness_traverse
    if ht is not None and "depth_mm" in ht:
        curves = {label: ht[col] for col, label in (("HRC_from_bore", "from the bore"), ("HRC_from_od", "from the OD"))
                  if col in ht}
        threshold = (run.summary or {}).get("hardness", {}).get("threshold_HRC")
        items.append(Item("image", "Hardness-depth traverse",
                          image=plots.hardness_traverse(ht["depth_mm"], curves, threshold, run.title)))
    else:
        missing.append("hardness-depth traverse: no hardness_traverse.csv")
    ol = run.outline
    if ol is not None and {"r_before_mm", "z_before_mm", "r_after_mm", "z_after_mm"} <= set(ol):
        items.append(Item("image", "Distortion x10 over the pre-quench outline",
                          image=plots.distortion(ol["r_before_mm"], ol["z_before_mm"], ol["r_after_mm"],
                                                 ol["z_after_mm"], run.title, "outline.csv")))
    else:
        missing.append("distortion plot: no outline.csv (written by runs with mechanics)")
    hoop = run.hoop_traverse
    if hoop is not None and "r_mm" in hoop:
        curves = {label: hoop[col] for col, label in (("hoop_MPa", "hoop"), ("axial_MPa", "axial")) if col in hoop}
        items.append(Item("image", "Residual hoop-stress traverse",
                          image=plots.stress_traverse(hoop["r_mm"], curves, run.title)))
    else:
        missing.append("residual hoop-stress traverse: no residual_hoop_traverse.csv (written by runs with mechanics)")
    items += _dimension_table(run, missing)
    items += _tempered_table(run)
    missing += run.notes
    if missing:
        items.append(Item("missing", "Not in this run directory", rows=[[m] for m in missing]))
    return Section(f"Run: {run.title} ({run.path.name})", items)


# -- sweep directory ------------------------------------------------------------------------------------
def response_columns(rows: list[dict[str, Any]]) -> list[str]:
    """The result columns of :data:`RESPONSE_OUTPUTS` that vary between the rows (at most MAX_RESPONSES)."""
    columns = list(dict.fromkeys(k for r in rows for k in r))
    chosen: list[str] = []
    for pattern in RESPONSE_OUTPUTS:
        regex = re.compile("^" + re.escape(pattern).replace(r"\*", "[^.]+") + ("" if pattern.endswith(".") else "$"))
        for c in columns:
            values = [r.get(c) for r in rows if isinstance(r.get(c), float)]
            if regex.match(c) and c not in chosen and len(set(values)) > 1:
                chosen.append(c)
    return chosen[:MAX_RESPONSES]


def sweep_section(path: Path) -> Section:
    """The results table and response plots of a sweep directory."""
    from quenchsim.sweep import RESULTS_CSV, SWEEP_JSON, read_results

    meta = json.loads((path / SWEEP_JSON).read_text())
    params: list[str] = meta.get("parameters", [])
    rows = read_results(path / RESULTS_CSV)
    ok = [r for r in rows if r["status"] in files.FINISHED_STATUSES]
    hot = sum(r["status"] == "hot" for r in rows)
    n_cases = len(meta.get("cases", [])) or len(rows)
    items = [Item("text", "Sweep", text=(f"Base case {meta.get('case')}, condition {meta.get('condition')}; "
                                         f"swept: {', '.join(params)}. {len(ok) - hot} of {n_cases} cases ok, "
                                         f"{hot} finished with the part still hot (status hot: their results are "
                                         f"those of the hot part), {len(rows) - len(ok)} failed, "
                                         f"{n_cases - len(rows)} not run."))]
    outputs = response_columns(ok)
    header = ["case", "status", *params, *outputs]
    items.append(Item("table", "Results (key outputs; all columns in results.csv)", header=header,
                      rows=[[mm(r.get(c)) if is_length(c) else r.get(c) for c in header] for r in rows]))
    failed = [[r["case"], r.get("error")] for r in rows if r["status"] not in files.FINISHED_STATUSES]
    if failed:
        items.append(Item("table", "Failed cases", header=["case", "error"], rows=failed))
    missing = []
    if ok and outputs:
        for x in params:
            others = [p for p in params if p != x]
            items.append(Item("image", f"Responses against {x}",
                              image=plots.responses(ok, x, others, outputs, f"{meta.get('name', path.name)}: "
                                                                            f"outputs against {x}")))
    else:
        missing.append("response plots: no finished cases with varying outputs")
    if missing:
        items.append(Item("missing", "Not in this sweep directory", rows=[[m] for m in missing]))
    return Section(f"Sweep: {meta.get('name', path.name)} ({path.name})", items)


def comparison_section(runs: list[RunResults]) -> Section:
    """Key outputs of several runs side by side."""
    keys = [("status", ("status",)), ("core HRC", ("hardness", "core_HRC")),
            ("HRC58 depth bore (mm)", ("hardness", "depth_mm", "HRC58_bore_mid")),
            ("HRC58 depth OD (mm)", ("hardness", "depth_mm", "HRC58_od_mid")),
            ("ID change (mm)", ("dimensions_mm", "change", "id")),
            ("OD change (mm)", ("dimensions_mm", "change", "od")),
            ("width change (mm)", ("dimensions_mm", "change", "width")),
            ("hoop stress OD surface (MPa)", ("residual_stress_MPa", "hoop", "od_surface_mid"))]

    def get(d: Any, path: tuple[str, ...]) -> Any:
        for k in path:
            d = d.get(k) if isinstance(d, dict) else None
        return d

    items = [Item("table", "Key outputs", header=["run", *[k for k, _ in keys]],
                  rows=[[r.title, files.run_status(r.summary),
                         *[(mm if "(mm)" in k else fmt)(get(r.summary or {}, p)) for k, p in keys[1:]]] for r in runs])]
    labels = [f"{r.title} ({r.path.name})" for r in runs]
    probes = [n for n in dict.fromkeys(k for r in runs if r.probes for k in r.probes) if n != "time_s"]
    panels = {name[:-2] if name.endswith("_C") else name:
              {label: (r.probes["time_s"], r.probes[name]) for label, r in zip(labels, runs)
               if r.probes and name in r.probes} for name in probes}
    if panels:
        items.append(Item("image", "Cooling curves compared",
                          image=plots.compare_curves(panels, "time (s)", "temperature (C)",
                                                     "Cooling curves at the probes, run by run", log_x=True)))
    traverse = {side: {label: (r.hardness_traverse["depth_mm"], r.hardness_traverse[col])
                       for label, r in zip(labels, runs) if r.hardness_traverse and col in r.hardness_traverse}
                for side, col in (("from the bore", "HRC_from_bore"), ("from the OD", "HRC_from_od"))}
    traverse = {k: v for k, v in traverse.items() if v}
    if traverse:
        items.append(Item("image", "Hardness-depth traverses compared",
                          image=plots.compare_curves(traverse, "depth at mid-width (mm)", "hardness (HRC)",
                                                     "Hardness-depth traverses, run by run")))
    return Section("Comparison of the runs", items)


# -- rendering ------------------------------------------------------------------------------------------
CSS = """body{font-family:sans-serif;max-width:1200px;margin:1em auto;padding:0 1em;color:#222}
table{border-collapse:collapse;margin:0.5em 0 1em}td,th{border:1px solid #bbb;padding:2px 6px;font-size:0.85em}
th{background:#eee}td{text-align:right}td:first-child{text-align:left}figure{margin:1em 0}
img{max-width:100%;height:auto}figcaption{font-size:0.9em;color:#444}.missing{color:#a33}"""


def _slug(text: str) -> str:
    return re.sub(r"[^a-z0-9]+", "_", text.lower()).strip("_")[:60]


def render_html(sections: list[Section], title: str, sources: list[str]) -> str:
    esc = html.escape
    out = ["<!DOCTYPE html>", '<html lang="en"><head><meta charset="utf-8">', f"<title>{esc(title)}</title>",
           f"<style>{CSS}</style></head><body>", f"<h1>{esc(title)}</h1>",
           f"<p>Generated {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC from: "
           f"{esc(', '.join(sources))}</p>", "<nav><ul>"]
    out += [f'<li><a href="#{s.anchor}">{esc(s.title)}</a></li>' for s in sections]
    out.append("</ul></nav>")
    for s in sections:
        out.append(f'<section id="{s.anchor}"><h2>{esc(s.title)}</h2>')
        for it in s.items:
            if it.kind == "image":
                data = base64.b64encode(it.image).decode("ascii")
                out.append(f'<figure><img alt="{esc(it.title)}" src="data:image/png;base64,{data}">'
                           f"<figcaption>{esc(it.title)}</figcaption></figure>")
            elif it.kind == "table":
                out.append(f"<h3>{esc(it.title)}</h3><table><tr>" + "".join(f"<th>{esc(h)}</th>" for h in it.header)
                           + "</tr>")
                out += ["<tr>" + "".join(f"<td>{esc(fmt(v))}</td>" for v in row) + "</tr>" for row in it.rows]
                out.append("</table>")
            elif it.kind == "missing":
                out.append(f'<h3>{esc(it.title)}</h3><ul class="missing">'
                           + "".join(f"<li>{esc(r[0])}</li>" for r in it.rows) + "</ul>")
            else:
                out.append(f"<p>{esc(it.text)}</p>")
        out.append("</section>")
    out.append("</body></html>")
    return "\n".join(out)


def render_markdown(sections: list[Section], title: str, sources: list[str], png_dir: Path,
                    md_dir: Path) -> tuple[str, list[Path]]:
    """The report as Markdown; images are written into ``png_dir`` and linked relative to ``md_dir``."""
    def cell(v: Any) -> str:
        return fmt(v).replace("|", "\\|").replace("\n", " ")

    lines = [f"# {title}", "", f"Generated from: {', '.join(sources)}", ""]
    pngs: list[Path] = []
    for si, s in enumerate(sections):
        lines += [f"## {s.title}", ""]
        for it in s.items:
            if it.kind == "image":
                png = png_dir / f"{si:02d}_{_slug(it.title)}.png"
                png.write_bytes(it.image)
                pngs.append(png)
                lines += [f"![{it.title}]({png.relative_to(md_dir).as_posix()})", ""]
            elif it.kind == "table":
                lines += [f"**{it.title}**", "", "| " + " | ".join(it.header) + " |",
                          "|" + "---|" * len(it.header)]
                lines += ["| " + " | ".join(cell(v) for v in row) + " |" for row in it.rows]
                lines.append("")
            elif it.kind == "missing":
                lines += [f"**{it.title}**", ""] + [f"- {r[0]}" for r in it.rows] + [""]
            else:
                lines += [it.text, ""]
    return "\n".join(lines), pngs


def write_report(dirs: list[str | Path], out_html: str | Path, title: str = "quenchsim report") -> list[Path]:
    """Write ``out_html`` and ``out_html`` with suffix ``.md`` (+ its PNGs in ``<stem>_files/``); returns the paths."""
    paths = [Path(d) for d in dirs]
    if not paths:
        raise InputError("RUN_DIR", None, "give at least one run or sweep directory")
    sections: list[Section] = []
    runs: list[RunResults] = []
    for p in paths:
        if not p.is_dir():
            raise InputError("RUN_DIR", str(p), "is not a directory")
        if is_sweep_dir(p):
            sections.append(sweep_section(p))
        else:
            run = load(p)
            if run.summary is None and run.frame is None and run.probes is None:
                raise InputError("RUN_DIR", str(p), "holds no run output (summary.json, results_*.vtu, probes.csv)")
            runs.append(run)
            sections.append(run_section(run))
    if len(runs) > 1:
        sections.insert(0, comparison_section(runs))
    out_html = Path(out_html)
    out_html.parent.mkdir(parents=True, exist_ok=True)
    sources = [str(p) for p in paths]
    out_html.write_text(render_html(sections, title, sources))
    md = out_html.with_suffix(".md")
    png_dir = out_html.parent / f"{out_html.stem}_files"
    png_dir.mkdir(exist_ok=True)
    for old in png_dir.glob("*.png"):
        old.unlink()
    text, pngs = render_markdown(sections, title, sources, png_dir, md.parent)
    md.write_text(text)
    return [out_html, md, *pngs]
