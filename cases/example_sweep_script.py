"""Example case script: build a ring case in code, sweep its wall thickness, plot hardness against it.

A thin ring hardens through; as the wall gets thicker the core cools more slowly and ends softer --
the hardenability question a heat treater asks of every new ring size. The case is a small SUJ3
ring quenched in oil with the generic mineral-oil HTC table of cases/crb_outer_ring.toml, then
cooled in still air (a constant-ish air HTC table keeps the example fast).

    python cases/example_sweep_script.py --out runs/example_sweep            # serial, in this process
    python cases/example_sweep_script.py --out runs/example_sweep --workers 2  # on a Dask LocalCluster

Writes OUT/<case>/ run folders, OUT/results.csv and OUT/hardness_vs_wall.png. Running it again
reuses the finished cases.
"""

from __future__ import annotations

import argparse
import copy
from pathlib import Path
from typing import Any

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from quenchsim.results import files  # noqa: E402
from quenchsim.sweep import make_sweep, run_sweep  # noqa: E402

OIL_HTC = {"T_C": [50, 150, 250, 350, 450, 550, 650, 750, 850],
           "h_W_m2K": [300, 400, 600, 1200, 2500, 4000, 2000, 600, 400],
           "ambient_C": 80.0}
"""Generic medium-speed mineral oil, as in cases/crb_outer_ring.toml (docs/reference/materials_and_kinetics.md sec. 3)."""
AIR_HTC = {"T_C": [25, 850], "h_W_m2K": [10, 90], "ambient_C": 25.0}
"""Still air: natural convection ~10 W/m2K near room temperature plus radiation (~80 W/m2K at 850 C, eps 0.8)."""


def build_case(inner_diameter_mm: float = 40.0, wall_mm: float = 10.0, width_mm: float = 20.0,
               mesh_mm: float = 3.0, quench_time_s: float = 90.0, air_time_s: float = 60.0) -> dict[str, Any]:
    """A small SUJ3 ring quenched in oil, as the table a case file would hold."""
    return {
        "name": "example_ring",
        "material": "SUJ3",
        "geometry": {"type": "rectangular", "inner_diameter_mm": inner_diameter_mm,
                     "outer_diameter_mm": inner_diameter_mm + 2.0 * wall_mm, "width_mm": width_mm, "chamfer_mm": 1.0},
        "mesh": {"size_mm": mesh_mm, "surface_size_mm": mesh_mm / 2.0, "surface_layer_mm": mesh_mm},
        "quench": {"time_s": quench_time_s, "htc_model": "table", "htc_table": copy.deepcopy(OIL_HTC)},
        "air": {"time_s": air_time_s, "htc_model": "table", "htc_table": copy.deepcopy(AIR_HTC)},
        "output": {"frames": 6},
        "mechanics": {"enabled": False},     # hardness needs the thermal and phase stages only
        "probes": [{"name": "near_bore", "r_mm": inner_diameter_mm / 2.0 + 1.0, "z_mm": width_mm / 2.0}],
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=Path("runs/example_sweep"))
    parser.add_argument("--workers", type=int, default=0, help="0: serial in this process; N: Dask LocalCluster")
    parser.add_argument("--walls-mm", type=float, nargs="+", default=[5.0, 10.0, 20.0])
    parser.add_argument("--quench-time-s", type=float, default=90.0)
    parser.add_argument("--air-time-s", type=float, default=60.0)
    args = parser.parse_args(argv)

    inner = 40.0
    case = build_case(inner_diameter_mm=inner, quench_time_s=args.quench_time_s, air_time_s=args.air_time_s)
    spec = make_sweep(case, grid={"geometry.outer_diameter_mm": [inner + 2.0 * w for w in args.walls_mm]},
                      name="example_wall")
    outcome = run_sweep(spec, args.out, workers=args.workers, progress=False)
    ok = [row for row in outcome.rows if row["status"] in files.FINISHED_STATUSES]
    hot = [row["case"] for row in ok if row["status"] == "hot"]
    if hot:   # the air stage was too short for these: their hardness is that of the part still warm
        print(f"note: still hot at the end (status hot; lengthen --air-time-s): {', '.join(hot)}")
    if not ok:
        print(f"no case finished; see {args.out / 'results.csv'}")
        return 1
    wall = [(row["geometry.outer_diameter_mm"] - inner) / 2.0 for row in ok]
    fig, ax = plt.subplots(figsize=(6.0, 4.0))
    ax.plot(wall, [row["hardness.core_HRC"] for row in ok], "o-", label="core (mid-wall, mid-width)")
    ax.plot(wall, [row["hardness.surface_HRC.bore_mid"] for row in ok], "s--", label="bore surface, mid-width")
    ax.set_xlabel("wall thickness (mm)")
    ax.set_ylabel("hardness (HRC)")
    ax.set_title(f"SUJ3 ring ID {inner:g} mm, oil {args.quench_time_s:g} s + air {args.air_time_s:g} s")
    ax.grid(True, lw=0.3)
    ax.legend()
    fig.tight_layout()
    png = args.out / "hardness_vs_wall.png"
    fig.savefig(png, dpi=110)
    plt.close(fig)
    for w, row in zip(wall, ok):
        print(f"wall {w:5.1f} mm: core {row['hardness.core_HRC']:5.1f} HRC, "
              f"bore surface {row['hardness.surface_HRC.bore_mid']:5.1f} HRC")
    print(f"plot: {png}")
    return 0 if outcome.failed == 0 else 1


if __name__ == "__main__":
    raise SystemExit(main())
