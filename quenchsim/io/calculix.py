"""CalculiX (ccx) as a peer of the stress solver: input writer from quenchsim's own mesh, temperature history
and material model, and readers of its results.

The section's quadratic triangles (scikit-fem ``MeshTri`` + ``ElementTriP2``) become CAX6 elements, node k+1
of the deck being scalar P2 DOF k (vertices first, then edge mid-points), so a CalculiX nodal field maps
one-to-one onto quenchsim's vector-P2 DOFs (2k, 2k+1) = (u_r, u_z).  The temperature of every node is given
per step (``*TEMPERATURE``; CalculiX ramps it linearly over the step), so both codes see one temperature
history.  The material is one phase of a :class:`~quenchsim.mechanics.MechanicsModel`, tabulated on a
temperature grid that holds every knot of its tables: ``*ELASTIC`` (E, nu, T), ``*EXPANSION, ZERO=T_aust``
(the secant coefficient eps_free(T) / (T - T_aust) of the quenchsim free strain, so the thermal strains agree
at the grid temperatures) and ``*PLASTIC`` (linear hardening: sigma_y(T) at eps_p = 0 and
sigma_y + H eps_p at eps_p = ``PLASTIC_STRAIN_END``).  SI units throughout (m, Pa, C).

File formats: CalculiX 2.20 User's Manual (G. Dhondt), sections 6.2.8 (axisymmetric elements), 7 (input
deck keywords) and 10 (the .frd result format).
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import Any

import numpy as np
from skfem import Basis, ElementTriP2, MeshTri

from quenchsim.errors import InputError

PLASTIC_STRAIN_END = 1.0
"""Second point of the *PLASTIC table (linear hardening is exact up to this equivalent plastic strain)."""


def p2_nodes(mesh: MeshTri) -> tuple[np.ndarray, np.ndarray]:
    """Node coordinates (n, 2) in scalar-P2 DOF order and the CAX6 connectivity (ne, 6), zero based
    (corners counter-clockwise, then the mid-side nodes of edges 1-2, 2-3, 3-1)."""
    basis = Basis(mesh, ElementTriP2(), intorder=1)
    nodes = basis.doflocs.T.copy()
    nv = mesh.p.shape[1]
    edge_of = {tuple(sorted(map(int, mesh.facets[:, f]))): nv + f for f in range(mesh.facets.shape[1])}
    t = mesh.t.T.copy()
    p = mesh.p
    area = ((p[0, t[:, 1]] - p[0, t[:, 0]]) * (p[1, t[:, 2]] - p[1, t[:, 0]])
            - (p[0, t[:, 2]] - p[0, t[:, 0]]) * (p[1, t[:, 1]] - p[1, t[:, 0]]))
    t[area < 0] = t[area < 0][:, [0, 2, 1]]
    mids = np.array([[edge_of[tuple(sorted((int(a), int(b))))] for a, b in ((e[0], e[1]), (e[1], e[2]), (e[2], e[0]))]
                     for e in t])
    conn = np.hstack([t, mids])
    # scikit-fem numbers facet DOFs after the vertices in facet order; check the node coordinates agree
    mid_xy = 0.5 * (p[:, t[:, 0]] + p[:, t[:, 1]]).T
    if not np.allclose(nodes[conn[:, 3]], mid_xy, atol=1e-12 * np.ptp(p)):
        raise RuntimeError("P2 DOF numbering differs from vertices-then-facets")
    return nodes, conn


def material_tables(model: Any, phase: str, T_C: np.ndarray) -> dict[str, np.ndarray]:
    """E, nu, secant expansion coefficient (relative to T_aust), yield stress and hardening modulus of one
    phase of a MechanicsModel at the temperatures ``T_C``."""
    from quenchsim.mechanics.model import phase_free_strain

    T = np.asarray(T_C, dtype=float)
    T0 = model.austenitizing_T_C
    X = {p: np.full(T.shape, 1.0 if p == phase else 0.0) for p in ("austenite", "pearlite", "bainite", "martensite")}
    eps = phase_free_strain(model, phase, T)
    dT = T - T0
    small = np.abs(dT) < 1e-6
    h = 1e-3  # the limit T -> T_aust: the instantaneous coefficient by a central difference
    slope = (phase_free_strain(model, phase, T0 + h) - phase_free_strain(model, phase, T0 - h)) / (2 * h)
    alpha = np.where(small, slope, eps / np.where(small, 1.0, dT))
    out = {"T_C": T, "E_Pa": model.E_Pa(T, X), "nu": model.nu(T, X), "alpha_secant_1_K": alpha}
    if model.plasticity:
        out["yield_Pa"] = model.yield_Pa(T, X)
        out["hardening_Pa"] = model.hardening_Pa(T, X)
    return out


def temperature_grid(model: Any, phase: str, T_min_C: float, T_max_C: float, step_K: float = 50.0) -> np.ndarray:
    """A grid over [T_min, T_max] every ``step_K`` that also holds every knot of the phase's E, nu, yield
    and hardening tables inside the range (so piecewise-linear tables are reproduced exactly)."""
    knots = [np.linspace(T_min_C, T_max_C, max(2, int(np.ceil((T_max_C - T_min_C) / step_K)) + 1))]
    props = [model.E_Pa, model.nu] + ([model.yield_Pa, model.hardening_Pa] if model.plasticity else [])
    for prop in props:
        sub = prop.for_phase(phase)
        if sub.kind == "table":
            knots.append(sub.T_C[(sub.T_C > T_min_C) & (sub.T_C < T_max_C)])
    return np.unique(np.round(np.concatenate(knots), 9))


def _rows(values: Iterable[Sequence[float]]) -> str:
    return "\n".join(", ".join(f"{v:.10g}" for v in row) for row in values)


def write_inp(path: str | Path, mesh: MeshTri, tables: dict[str, np.ndarray], T_initial_C: float,
              temperatures_C: Sequence[np.ndarray], step_times_s: Sequence[float], fixed_node: int,
              axis_nodes: Sequence[int] = ()) -> Path:
    """Write a CalculiX deck: CAX6 section, one material, ``*INITIAL CONDITIONS`` at T_initial, one
    ``*STATIC`` step per entry of ``temperatures_C`` (nodal temperatures in scalar-P2 DOF order) with the
    step's length from ``step_times_s`` (cumulative times), u_z = 0 at ``fixed_node`` (zero based), u_r = 0 at
    ``axis_nodes``; displacements (.dat) and nodal stresses (.frd) of the last step are requested."""
    nodes, conn = p2_nodes(mesh)
    n = len(nodes)
    if len(temperatures_C) != len(step_times_s) or not temperatures_C:
        raise InputError("calculix.temperatures_C", len(temperatures_C), f"one per step time ({len(step_times_s)})")
    lines = ["** quenchsim -> CalculiX peer deck (SI: m, Pa, C)", "*NODE, NSET=NALL"]
    lines += [f"{k + 1}, {x:.15g}, {y:.15g}" for k, (x, y) in enumerate(nodes)]
    lines.append("*ELEMENT, TYPE=CAX6, ELSET=EALL")
    lines += [f"{e + 1}, " + ", ".join(str(int(c) + 1) for c in row) for e, row in enumerate(conn)]
    lines += ["*NSET, NSET=NFIX", str(int(fixed_node) + 1), "*BOUNDARY", "NFIX, 2, 2"]
    if len(axis_nodes):
        lines += ["*NSET, NSET=NAXIS"] + [str(int(k) + 1) for k in axis_nodes] + ["*BOUNDARY", "NAXIS, 1, 1"]
    lines += ["*MATERIAL, NAME=PHASE", "*ELASTIC",
              _rows(zip(tables["E_Pa"], tables["nu"], tables["T_C"])),
              f"*EXPANSION, ZERO={T_initial_C:.10g}", _rows(zip(tables["alpha_secant_1_K"], tables["T_C"]))]
    if "yield_Pa" in tables:
        lines.append("*PLASTIC")
        for sy, H, T in zip(tables["yield_Pa"], tables["hardening_Pa"], tables["T_C"]):
            lines.append(_rows([(sy, 0.0, T), (sy + H * PLASTIC_STRAIN_END, PLASTIC_STRAIN_END, T)]))
    lines += ["*SOLID SECTION, ELSET=EALL, MATERIAL=PHASE", "*INITIAL CONDITIONS, TYPE=TEMPERATURE",
              f"NALL, {T_initial_C:.10g}"]
    previous = 0.0
    for i, (T, t) in enumerate(zip(temperatures_C, step_times_s)):
        T = np.asarray(T, dtype=float)
        if T.shape != (n,):
            raise InputError(f"calculix.temperatures_C[{i}]", T.shape, f"must hold the {n} P2 node temperatures")
        length = max(float(t) - previous, 1e-6)
        previous = float(t)
        lines += ["*STEP, INC=1000", "*STATIC", f"{length:.10g}, {length:.10g}", "*TEMPERATURE"]
        lines += [f"{k + 1}, {v:.10g}" for k, v in enumerate(T)]
        if i == len(temperatures_C) - 1:
            lines += ["*NODE PRINT, NSET=NALL", "U", "*NODE FILE", "U", "*EL FILE", "S, PEEQ"]
        lines.append("*END STEP")
    path = Path(path)
    path.write_text("\n".join(lines) + "\n")
    return path


def read_dat_displacements(path: str | Path, n_nodes: int) -> np.ndarray:
    """(n_nodes, 2) displacements (u_r, u_z) of the last ``displacements`` block of a .dat file."""
    text = Path(path).read_text()
    blocks = [m.end() for m in re.finditer(r"displacements \(vx,vy,vz\)[^\n]*\n", text)]
    if not blocks:
        raise InputError(str(path), "no displacements", "the .dat file holds no *NODE PRINT U block")
    u = np.full((n_nodes, 2), np.nan)
    for line in text[blocks[-1]:].splitlines():
        parts = line.split()
        if not parts:
            if np.isfinite(u).all():
                break
            continue
        if len(parts) < 3 or not parts[0].isdigit():
            break
        k = int(parts[0]) - 1
        if k < n_nodes:
            u[k] = float(parts[1]), float(parts[2])
    if not np.isfinite(u).all():
        raise InputError(str(path), "displacements", f"missing for {int(np.sum(~np.isfinite(u[:, 0])))} nodes")
    return u


def read_frd_block(path: str | Path, name: str, n_nodes: int) -> np.ndarray:
    """The last nodal result block ``name`` (e.g. "STRESS", "DISP") of an ASCII .frd file as (n_nodes,
    n_components); nodes that CalculiX adds (expanded axisymmetric elements) are dropped."""
    lines = Path(path).read_text().splitlines()
    starts = [i for i, line in enumerate(lines) if line.split()[:2] == ["-4", name]]
    if not starts:
        raise InputError(str(path), name, "no such result block in the .frd file")
    i = starts[-1]
    n_comp = int(lines[i].split()[2])
    out = np.full((n_nodes, n_comp), np.nan)
    i += 1
    while lines[i].startswith(" -5"):
        i += 1
    while not lines[i].startswith(" -3"):
        line = lines[i]
        if line.startswith(" -1"):
            k = int(line[3:13]) - 1
            values = [float(line[13 + 12 * j:25 + 12 * j]) for j in range(min(6, n_comp))]
            if 0 <= k < n_nodes:
                out[k, :len(values)] = values
        i += 1
    return out


def run_ccx(deck: Path, ccx: str = "ccx", timeout_s: float = 3600.0) -> None:
    """Run ``ccx -i JOB`` in the deck's folder with one thread; raise with the log tail when it fails."""
    import os
    import subprocess

    env = {**os.environ, "OMP_NUM_THREADS": "1", "CCX_NPROC_EQUATION_SOLVER": "1"}
    res = subprocess.run([ccx, "-i", deck.stem], cwd=deck.parent, capture_output=True, text=True,
                         timeout=timeout_s, env=env)
    (deck.parent / f"{deck.stem}.log").write_text(res.stdout + res.stderr)
    if res.returncode != 0 or "*ERROR" in res.stdout:
        tail = "\n".join((res.stdout + res.stderr).splitlines()[-15:])
        raise RuntimeError(f"ccx failed on {deck}:\n{tail}")
