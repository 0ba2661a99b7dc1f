"""`quenchsim material fit DATA.toml [--out materials/NAME.toml] [--plots DIR] [--json]`: steel kinetics from CCT/TTT/Jominy data.

Fits the free ``c_curve`` parameters named in the data file's [fit] tables by integrating the simulation's own
additivity along every data point (:mod:`quenchsim.fitting.kinetics`), prints the parameters and the residual of
every point, and writes the data file's base material with the fitted reactions and the fit record (data file,
residuals, sources). A parameter the data cannot constrain stops the fit with its name (exit 2).

The written steel is the user's: its ``name`` is the output file's stem and its ``description`` says what it was fitted
to (the base material's are not kept). It goes to ``--out``, by default ``./materials/DATA.toml`` (the current
directory's data folder, where ``quenchsim run`` finds it by name: :mod:`quenchsim.materials`); an ``--out`` in the
shipped data folder is refused before any work. The data are checked for plausibility before the fit
(:func:`quenchsim.fitting.diagram_data.load_diagram_data`). A re-fit written over its own base material file keeps
that file's name and description (a maintainer regenerating a shipped steel, ``--replace-shipped``). The fit
writes no mechanics data: a run of the steel needs ``NAME.mechanics.toml`` beside it, or
``--set mechanics.enabled=false`` (docs/guide/bring_a_steel.md). After the fit its quality and the data's units are
checked (:mod:`quenchsim.fitting.fit_quality`): a poor fit or a likely unit slip is a WARNING on the terminal and
``fit_quality_flag = 1`` in the written file; a fit that stops names a unit slip in its error.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from quenchsim.commands.data_option import add_data_option
from quenchsim.fitting import fit_quality as fq
from quenchsim.fitting import kinetics as fk
from quenchsim.fitting.diagram_data import load_diagram_data
from quenchsim.materials import USER_DATA_FOLDER, find_data_file
from quenchsim.shipped import is_bare_name, refuse_shipped_file


def configure(parser: argparse.ArgumentParser) -> None:
    sub = parser.add_subparsers(dest="action", required=True)
    fit = sub.add_parser("fit", help="fit a steel's transformation kinetics to CCT / TTT / Jominy data")
    fit.add_argument("data_file", metavar="DATA.toml",
                     help="CCT / TTT / Jominy data file, or the name of one in a data folder's data/ (e.g. the shipped "
                          "100Cr6_kawulok2020_kaymak2007); a complete example: docs/guide/bring_a_steel.md, the "
                          "schema: python3 -m pydoc quenchsim.fitting.diagram_data")
    fit.add_argument("--out", type=Path, help="material file to write (default: materials/DATA.toml in the current "
                                              "folder, where a run finds it by name)")
    add_data_option(fit)
    fit.add_argument("--plots", type=Path, help="write CCT / TTT (/ Jominy) overlay PNGs into this folder")
    fit.add_argument("--json", action="store_true", help="print one JSON object instead of the tables")
    fit.add_argument("--replace-shipped", action="store_true",
                     help="maintainers: regenerate a shipped steel in place (e.g. --out materials/SUJ3.toml from "
                          "materials/data/SUJ3_from_100Cr6.toml); its name and description are kept")


def data_file_path(value: str) -> Path:
    """The data file of ``material fit``: a path, or a bare name (:func:`quenchsim.shipped.is_bare_name`) found in the
    ``data/`` folder of the data folders (:func:`quenchsim.materials.find_data_file`; the shipped
    ``materials/data/`` last)."""
    return find_data_file(value, "data", field="DATA.toml") if is_bare_name(value) else Path(value)


def run(args: argparse.Namespace) -> int:
    args.data_file = data_file_path(args.data_file)   # after --data is applied (quenchsim.cli.main)
    out = args.out or Path(USER_DATA_FOLDER) / f"{args.data_file.stem}.toml"
    if not args.replace_shipped:
        refuse_shipped_file(out, hint="maintainers regenerating it: --replace-shipped")
    data = load_diagram_data(args.data_file)
    base = find_data_file(data.material, field=f"{data.path.name}: material")
    histories = fk.jominy_histories(data, progress=not args.json)
    slips = fq.slips_against_base(data)
    try:
        result = fk.fit_kinetics(data, histories)
    except fk.FitError as exc:
        slips = slips or fq.slips_by_refit(data, histories, None)
        if slips:
            raise fk.FitError(f"{exc}; {slips[0]}") from None
        raise
    poor = fq.quality_warning(result)
    if poor and not slips:
        slips = fq.slips_by_refit(data, histories, result)
    warnings = [w for w in (poor, *slips) if w]
    own = out.resolve() != base.resolve()   # a new steel: the user's name; one re-fitted in place keeps its own
    out = fk.write_material(result, out, str(args.data_file), name=out.stem if own else None,
                            description=f"{out.stem}: kinetics fitted by `quenchsim material fit {args.data_file}` "
                                        f"({data.name}); the other data from {data.material}",
                            quality=fq.fit_record(result, warnings))
    if args.plots:
        from quenchsim.fitting.plots import plot_cct_overlay, plot_jominy, plot_ttt
        from quenchsim.metallurgy import hv_to_hrc

        kin = result.kinetics
        plot_cct_overlay(kin, data, args.plots / f"{out.stem}_cct.png")
        plot_ttt(kin, data, args.plots / f"{out.stem}_ttt.png")
        if histories is not None:
            _, hv = fk.run_histories(kin, *histories)
            plot_jominy([p.distance_mm for p in data.jominy], hv_to_hrc(hv), data.jominy,
                        args.plots / f"{out.stem}_jominy.png", f"{kin.material}: Jominy")
    if args.json:
        print(json.dumps({"material_file": str(out), "parameters": result.parameters, "std_errors": result.std_errors,
                          "cost": result.cost,
                          "residuals": [{"point": r.where, "quantity": r.quantity, "data": r.data, "model": r.model,
                                         "unit": r.unit, "normalised": r.residual, "kind": r.kind} for r in result.residuals],
                          **fq.fit_record(result, warnings)}))
        return 0
    print(f"{data.name}: {len(result.residuals)} compared quantities, cost {result.cost:.4g}")
    for r, values in result.parameters.items():
        spec = data.fit[r]
        cells = []
        for p, v in values.items():
            tag = "fitted" if p in spec.free else "fixed"
            err = result.std_errors[r].get(p)
            cells.append(f"{p} = {_numbers(v, '.5g')} ({tag}"
                         + (f", +-{_numbers(err, '.2g')}{' rel' if p == 'tau_ref_s' else ''})" if err else ")"))
        print(f"  {r}: " + "; ".join(cells))
        if spec.tau_factor != 1.0:
            print(f"  {r}: tau_ref_s x {spec.tau_factor:g} written to the material (declared calibration)")
    print(f"{'point':<40} {'quantity':<22} {'data':>9} {'model':>9} {'unit':<4} {'norm.':>6} kind")
    for x in result.residuals:
        print(f"{x.where[:40]:<40} {x.quantity:<22} {x.data:9.4g} {x.model:9.4g} {x.unit:<4} {x.residual:6.2f} {x.kind}")
    print(f"wrote {out}")
    for warning in warnings:
        print(f"WARNING: {warning}")
    if warnings:
        print("(the file's fit record says fit_quality_flag = 1, with these warnings)")
    if not (out.parent / f"{out.stem}.mechanics.toml").is_file():
        print(f"note: no {out.stem}.mechanics.toml beside it: a run of this steel needs one for dimensions and "
              "stresses, or --set mechanics.enabled=false (docs/guide/bring_a_steel.md)")
    return 0


def _numbers(v: float | tuple[float, ...], spec: str) -> str:
    """A fitted value, or the list of a piecewise n(T)'s node values."""
    return "[" + ", ".join(format(x, spec) for x in v) + "]" if isinstance(v, tuple) else format(v, spec)
