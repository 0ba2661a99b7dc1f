"""`quenchsim mesh CASE.toml [--condition N] [--out FILE.msh] [--png FILE]`: build the section mesh."""

from __future__ import annotations

import argparse
from pathlib import Path

from quenchsim.case import load_case
from quenchsim.errors import require
from quenchsim.geometry import mesh_profile
from quenchsim.geometry.profile import MM


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("case", type=Path)
    parser.add_argument("--condition")
    parser.add_argument("--out", type=Path, help="write the gmsh .msh file here")
    parser.add_argument("--mesh-size", type=float, help="core element size in mm")
    parser.add_argument("--png", type=Path, help="plot the mesh with its named boundary segments")


def run(args: argparse.Namespace) -> int:
    case = load_case(args.case, args.condition)
    if args.mesh_size is not None:
        require(args.mesh_size > 0, "--mesh-size", args.mesh_size, "must be > 0 (mm)")
        case = case.with_mesh_size(args.mesh_size)
    section = mesh_profile(case.profile, case.mesh.size_mm * MM, case.mesh.surface_size_mm * MM,
                           case.mesh.surface_layer_mm * MM, msh_path=args.out)
    print(f"{section.n_elements} triangles, {section.mesh.p.shape[1]} nodes; segments: "
          + ", ".join(f"{k} ({len(v)} edges)" for k, v in section.boundaries.items()))
    if args.png:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(5, 8))
        p = section.mesh.p / MM
        ax.triplot(p[0], p[1], section.mesh.t.T, lw=0.3, color="0.5")
        for name, facets in section.boundaries.items():
            f = section.mesh.facets[:, facets]
            ax.plot(p[0][f], p[1][f], lw=2)
            ax.plot([], [], lw=2, label=name)
        ax.set_aspect("equal")
        ax.set_xlabel("r (mm)")
        ax.set_ylabel("z (mm)")
        ax.legend(fontsize=7)
        fig.savefig(args.png, dpi=150, bbox_inches="tight")
    return 0
