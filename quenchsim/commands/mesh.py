"""`quenchsim mesh CASE.toml [--condition N] [--out FILE.msh] [--png FILE]`: build the section mesh."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

import numpy as np

from quenchsim.case import load_case
from quenchsim.commands.mesh_limit import MAX_TRIANGLES, refuse_large_mesh
from quenchsim.figures import subplots
from quenchsim.errors import require
from quenchsim.geometry import SectionMesh, mesh_profile
from quenchsim.geometry.profile import MM
from quenchsim.shipped import resolve_case


def configure(parser: argparse.ArgumentParser) -> None:
    parser.description = ("Build the section mesh of a case and print its size and named boundary segments "
                          "(files only with --out / --png).")
    parser.add_argument("case", type=Path, help="case file (TOML), or the name of a shipped case (quenchsim cases), e.g. crb_outer_ring")
    parser.add_argument("--condition", help="named condition of the case file (required when it has conditions; "
                                            "the geometry and mesh may differ between them)")
    parser.add_argument("--out", type=Path, help="write the gmsh .msh file here")
    parser.add_argument("--mesh-size", type=float, help="core element size in mm (surface size scales with it; "
                                                        "default: the case's mesh.size_mm)")
    parser.add_argument("--png", type=Path, help="plot the mesh with its named boundary segments")
    parser.add_argument("--force", action="store_true", help=f"mesh above {MAX_TRIANGLES:,} estimated triangles")


def run(args: argparse.Namespace) -> int:
    case = load_case(resolve_case(args.case), args.condition)
    if args.mesh_size is not None:
        require(args.mesh_size > 0, "--mesh-size", args.mesh_size, "must be > 0 (mm)")
        case = case.with_mesh_size(args.mesh_size)
    refuse_large_mesh(case, args.force)
    section = mesh_profile(case.profile, case.mesh.size_mm * MM, case.mesh.surface_size_mm * MM,
                           case.mesh.surface_layer_mm * MM, msh_path=args.out)
    print(f"{section.n_elements} triangles, {section.mesh.p.shape[1]} nodes; segments: "
          + ", ".join(f"{k} ({len(v)} edges)" for k, v in section.boundaries.items()))
    if args.png:
        segments_figure(section).savefig(args.png, dpi=150, bbox_inches="tight")
    return 0


def segments_figure(section: SectionMesh) -> Any:
    """The mesh with every named boundary segment drawn in one colour of its own, named in the legend."""
    from matplotlib import colormaps
    from matplotlib.collections import LineCollection

    fig, ax = subplots(figsize=(5, 8))
    p = section.mesh.p / MM
    ax.triplot(p[0], p[1], section.mesh.t.T, lw=0.3, color="0.6")
    colours = colormaps["tab10" if len(section.boundaries) <= 10 else "tab20"]
    for i, (name, facets) in enumerate(section.boundaries.items()):
        f = section.mesh.facets[:, facets]                       # (2, n) vertex indices of the segment's edges
        edges = np.stack([p[:, f[0]].T, p[:, f[1]].T], axis=1)   # (n, 2 points, 2 coordinates)
        ax.add_collection(LineCollection(list(edges), colors=[colours(i)], linewidths=2.5, label=name))
    ax.set_aspect("equal")
    ax.set_xlabel("r (mm)")
    ax.set_ylabel("z (mm)")
    ax.legend(fontsize=7, loc="center left", bbox_to_anchor=(1.02, 0.5))
    return fig
