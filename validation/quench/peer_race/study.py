"""Code-to-code: the quenched 100Cr6 bearing race of Furlan et al. (2025), thermo-elastic, rebuilt as
cases/peer_race_100Cr6.toml with materials/100Cr6_furlan*.toml (their kinetics, elastic data, transformation
strains and water HTC table); their final phase fractions and three displacements are the targets."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from quenchsim.case import load_case
from quenchsim.results import files, load_frame
from quenchsim.results import load as load_run
from quenchsim.validation import ROOT, cached_run, study_module

TITLE = "Code-to-code: quenched 100Cr6 bearing race (Furlan et al. 2025, thermo-elastic)"
SLOW = True
PEER = ROOT / "cases" / "peer_race_100Cr6.toml"
POINTS_M = {"radial_at_150_m75": (0.150, -0.075, "r"), "radial_at_205_m137p5": (0.205, -0.1375, "r"),
            "axial_top_at_r155": (0.155, 0.0, "z")}
"""Where the peer's displacements were read: (r, z) in the hot (austenitised) geometry, component."""


def run(workdir: Path) -> dict[str, Any]:
    from skfem import Basis, ElementTriP1, MeshTri

    workdir = Path(workdir)
    run_dir = cached_run(load_case(PEER), study_module("quench/ring_a").run_dirs(workdir) / "peer_race_100Cr6")
    result = load_run(run_dir)
    final, hot = result.frame, load_frame(sorted(run_dir.glob(f"{files.SERIES_NAME}_*.vtu"))[0])
    # the peer's displacements are from the hot (austenitised) geometry with its fixed node, the section of the
    # first frame (the last frame lies on the "before" section; the vertex order is the same)
    mesh = MeshTri(np.ascontiguousarray(hot.points[:, :2].T), np.ascontiguousarray(hot.triangles.T))
    basis = Basis(mesh, ElementTriP1())
    u = final.point_data["displacement_from_start_m"][:, :2]   # from the hot section, the peer's fixed node held
    # the points are nudged 1e-7 m into the section (they lie on its boundary)
    pts = np.array([[p[0] for p in POINTS_M.values()], [p[1] for p in POINTS_M.values()]])
    eps = 1e-7
    inside = pts + np.array([[eps, -eps, 0.0], [0.0, 0.0, -eps]])
    P = basis.probes(inside)
    ur, uz = P @ u[:, 0], P @ u[:, 1]
    disp = {k: float((ur if comp == "r" else uz)[i] * 1e3) for i, (k, (_, _, comp)) in enumerate(POINTS_M.items())}
    phases = {p: result.summary["phases_final"][p]["mean"] for p in ("martensite", "bainite", "austenite")}
    return {"phases_mean": phases, "displacement_mm": disp}


def page(metrics: dict[str, Any]) -> str:
    rows = ["Their values, the tolerances (phase fractions within 0.01 absolute, displacements within 2 %) and the "
            "comparison are in the targets table.", "", "| quantity | quenchsim |", "|---|---|"]
    rows += [f"| {p} (volume mean) | {v:.3f} |" for p, v in metrics["phases_mean"].items()]
    rows += [f"| {k} (mm) | {v:.3f} |" for k, v in metrics["displacement_mm"].items()]
    return "\n".join(rows)
