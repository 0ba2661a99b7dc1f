"""`quenchsim quenchant fit | from-datasheet | show`: a quenchant's still-bath h(T_surface) from its ISO 9950 curve.

    quenchsim quenchant fit CURVE.csv [--out materials/quenchants/NAME.toml] [--source "..."] [--bath-temperature-C 40]
                                      [--agitation-m-s 0] [--tag "..."] [--png fit.png] [--fast]
    quenchsim quenchant from-datasheet --max-rate 93 --T-max-rate 602 --rate-300 5.4 [--t600 6 --t400 10.4
                                      --t200 40] --bath-temperature-C 60 --out NAME.toml --source "..."
    quenchsim quenchant show NAME

CURVE.csv has a header ``time_s,temperature_C`` (centre thermocouple of the ISO 9950 probe) or
``temperature_C,rate_C_s`` (its cooling-rate curve). The fit is an inverse heat conduction on quenchsim's own
thermal solver (quenchsim.fitting.quenchant); the data-sheet shortcut is an approximation and says so in the file.
Before the fit, the curve is checked against the probe's physical bounds (quenchsim.fitting.probe_bounds: time to
300 C, the conduction limit of its cooling rate); a fitted h(T_s) above the bound for an oil is warned about. The oil
is written to ``--out``, by default ``./materials/quenchants/NAME.toml`` (NAME: ``--name``, else the curve file's
stem), where ``quenchsim run`` finds it by name (:mod:`quenchsim.materials`); an ``--out`` in the shipped data
folder is refused; without ``--source`` the file records "not given by the user".
"""

from __future__ import annotations

import argparse
from pathlib import Path

from quenchsim.commands.data_option import add_data_option
from quenchsim.errors import InputError
from quenchsim.materials import USER_DATA_FOLDER
from quenchsim.shipped import refuse_shipped_file

NO_SOURCE = "not given by the user"
"""The ``source`` written when ``--source`` is not given: a placeholder, never an invented source."""


def configure(parser: argparse.ArgumentParser) -> None:
    sub = parser.add_subparsers(dest="action", required=True)
    fit = sub.add_parser("fit", help="h(T_s) from a measured probe curve (inverse heat conduction)")
    fit.add_argument("curve", type=Path, help="CSV: time_s,temperature_C or temperature_C,rate_C_s")
    _common(fit)
    fit.add_argument("--tag", default="", help="how the curve was obtained (e.g. 'read off Fig. 3, +-5 C')")
    fit.add_argument("--sigma", type=float, help="noise of the data (K, or K/s for a rate curve)")
    fit.add_argument("--fast", action="store_true", help="coarse nodes (100 K) and steps only: seconds, less accurate")
    sheet = sub.add_parser("from-datasheet", help="approximate h(T_s) from the data-sheet figures (stated as such)")
    sheet.add_argument("--max-rate", type=float, required=True, help="maximum cooling rate, C/s")
    sheet.add_argument("--T-max-rate", dest="T_max_rate", type=float, required=True, help="temperature of it, C")
    sheet.add_argument("--rate-300", type=float, required=True, help="cooling rate at 300 C, C/s")
    for t in (600, 400, 200):
        sheet.add_argument(f"--t{t}", type=float, help=f"time to {t} C, s (optional)")
    sheet.add_argument("--shape-from", default="astm_d6200_fast_oil",
                       help="quenchant or start-shape (quenchants/data/, e.g. bt2013_start_shape) whose [shape] "
                            "ratios the shortcut keeps: a name or a path")
    _common(sheet)
    show = sub.add_parser("show", help="print a still-bath curve")
    show.add_argument("name", help="a quenchant name (found as quenchsim run finds it) or a path")
    add_data_option(show)


def _common(p: argparse.ArgumentParser) -> None:
    p.add_argument("--out", type=Path, help="quenchant file to write (default: materials/quenchants/NAME.toml in the "
                                            "current folder, where a run finds it by name)")
    p.add_argument("--replace-shipped", action="store_true",
                   help="maintainers: write into the shipped materials/quenchants folder")
    add_data_option(p)
    p.add_argument("--name", help="quenchant name (default: the --out file's stem, else the curve file's stem)")
    p.add_argument("--source", default=NO_SOURCE,
                   help=f"where the curve / figures were published (default: \"{NO_SOURCE}\", recorded as such)")
    p.add_argument("--bath-temperature-C", dest="bath_C", type=float, default=40.0, help="bath temperature of the test")
    p.add_argument("--agitation-m-s", dest="agitation", type=float, default=0.0, help="agitation of the test (0 = still)")
    p.add_argument("--description", default="")
    p.add_argument("--png", type=Path, help="plot probe curve vs re-simulated curve and h(T_s)")


def _check_common(args: argparse.Namespace) -> None:
    """Where the oil is written (``args.out``, default ``./materials/quenchants/NAME.toml``) and the test
    conditions, checked before any work."""
    if args.out is None:
        name = args.name or (args.curve.stem if args.action == "fit" else None)
        if name is None:
            raise InputError("--out", None, "is required without --name (from-datasheet has no curve file to name "
                                            "the oil after)")
        args.out = Path(USER_DATA_FOLDER) / "quenchants" / f"{name}.toml"
    if not args.replace_shipped:
        refuse_shipped_file(args.out)
    if not -20.0 <= args.bath_C <= 300.0:
        raise InputError("--bath-temperature-C", args.bath_C, "must lie between -20 and 300 C")
    if not args.agitation >= 0.0:
        raise InputError("--agitation-m-s", args.agitation, "must be >= 0 m/s")


def run(args: argparse.Namespace) -> int:
    from quenchsim.fitting import quenchant as q

    if args.action == "show":
        from quenchsim.bath.quenchant import load_probe_quenchant

        oil = load_probe_quenchant(args.name, field="NAME")
        print(f"{oil.name}: bath {oil.bath_temperature_C:g} C, agitation {oil.agitation_m_s:g} m/s; "
              f"identified over {oil.identified_C[0]:.0f}-{oil.identified_C[1]:.0f} C")
        print(f"source: {oil.source}\nmethod: {oil.method}")
        print(f"{'T_s (C)':>10}{'h (W/m2K)':>12}")
        for T, h in zip(oil.T_C, oil.h_W_m2K):
            print(f"{T:>10.0f}{h:>12.0f}")
        return 0
    _check_common(args)
    from quenchsim.fitting.probe_bounds import check_probe_plausible, htc_warning

    if args.action == "fit":
        data = q.read_probe_csv(args.curve)
        check_probe_plausible(data.time_s, data.temperature_C, data.rate_C_s, where=args.curve.name)
        levels = ((100.0, 4.0),) if args.fast else ((100.0, 4.0), (50.0, 1.0))
        fit = q.fit_probe_curve(data, bath_C=args.bath_C, sigma=args.sigma, levels=levels)
        data_file = str(args.curve)
    else:
        check_probe_plausible(None, [args.T_max_rate, 300.0], [args.max_rate, args.rate_300], where="--max-rate")
        figures = {"CRmax_C_s": args.max_rate, "T_CRmax_C": args.T_max_rate, "CR300_C_s": args.rate_300}
        figures.update({f"t_to_{t}C_s": getattr(args, f"t{t}") for t in (600, 400, 200) if getattr(args, f"t{t}") is not None})
        fit = q.fit_figures(figures, bath_C=args.bath_C, shape=q.default_shape(args.shape_from))
        data_file = ""
        args.tag = "data-sheet figures"
    name = args.name or args.out.stem
    doc = q.quenchant_document(fit, name=name, source=args.source, tag=args.tag, agitation_m_s=args.agitation,
                               description=args.description, data_file=data_file)
    q.write_quenchant(args.out, doc)
    print(f"wrote {args.out}: {fit.T_C.size} nodes, residual rms {fit.residual_rms:.3g} {fit.residual_unit}, "
          f"{fit.seconds:.1f} s")
    for key in ("CRmax_C_s", "T_CRmax_C", "CR300_C_s"):
        print(f"  {key}: published/measured {fit.measured.get(key, float('nan')):.1f}, re-simulated {fit.simulated[key]:.1f}")
    warning = htc_warning(fit.T_C, fit.h_W_m2K)
    if warning:
        print(f"WARNING: {warning}")
    if args.source == NO_SOURCE:
        print(f"note: no --source given: the file records source = \"{NO_SOURCE}\"")
    if args.png:
        from quenchsim.fitting.plots import plot_probe_fit

        plot_probe_fit(fit, args.png, name)
        print(f"wrote {args.png}")
    return 0
