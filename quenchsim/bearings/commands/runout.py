"""`quenchsim bearings runout INPUT.toml`: ball-bearing run-out / NRRO from form errors.

Writes the ring-centre trajectory and spectra CSVs (and orbit / spectrum plots unless --no-plots) into --out
and returns the model, identified spectral peaks, run-out and NRRO as one JSON object.
"""

from __future__ import annotations

import argparse
import pathlib

from quenchsim.bearings.runout import load_case, run as run_case
from quenchsim.bearings.runout.output import summary, write_spectra_csv, write_trajectory_csv
from quenchsim.shipped import resolve_case


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("input", type=pathlib.Path, help="run-out case file (TOML), or a shipped one's name (runout_695_balls, ...: quenchsim cases)")
    parser.add_argument("--out", type=pathlib.Path, default=None,
                        help="output directory (default: runs/runout_<input stem>, or runs/<input stem> when that "
                             "starts with runout, below the current directory)")
    parser.add_argument("--no-plots", action="store_true", help="skip the orbit and spectrum PNGs")


def default_out(input_path: pathlib.Path) -> pathlib.Path:
    """Where a run-out case writes without --out: under runs/, as `quenchsim run` does (never a loose folder in the
    current directory)."""
    stem = input_path.stem
    return pathlib.Path("runs") / (stem if stem.startswith("runout") else f"runout_{stem}")


def run(args: argparse.Namespace) -> dict:
    case = load_case(resolve_case(args.input, field="input"))
    out = args.out if args.out is not None else default_out(args.input)
    result = run_case(case)
    csv = write_trajectory_csv(result, out / "trajectory.csv")
    data = summary(result, csv)
    data["spectra_csv"] = [str(p) for p in write_spectra_csv(result, out)]
    if not args.no_plots:
        from quenchsim.bearings.runout.plots import orbit_plot, spectrum_plot

        title = f"{args.input.name} ({case.model})"
        data["plots"] = [str(orbit_plot(result, out / "orbit.png", title)),
                         str(spectrum_plot(result, out / "spectrum.png", title))]
    return data
