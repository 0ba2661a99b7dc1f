"""Outputs written while a run goes: a PVD-indexed .vtu series and a probe CSV.

Both are flushed after every write so a run that stops keeps everything up to its last step.
The section lives in the x-y plane of the VTK files (x = r, y = z, metres).
"""

from __future__ import annotations

import csv
from pathlib import Path
from xml.sax.saxutils import quoteattr

import meshio
import numpy as np


class VtkSeries:
    """``results.pvd`` + ``frame_NNNN.vtu`` files; the PVD is rewritten after each frame (always valid)."""

    def __init__(self, out_dir: Path, points_rz: np.ndarray, triangles: np.ndarray, name: str = "results") -> None:
        self.out_dir = Path(out_dir)
        self.points = np.column_stack([points_rz.T, np.zeros(points_rz.shape[1])])
        self.cells = [("triangle", np.ascontiguousarray(triangles.T))]
        self.name = name
        self.frames: list[tuple[float, str]] = []

    def write(self, time_s: float, point_data: dict[str, np.ndarray], points_rz: np.ndarray | None = None) -> Path:
        """One frame; ``points_rz`` (2, n) replaces the series' point coordinates for this frame only."""
        fname = f"{self.name}_{len(self.frames):04d}.vtu"
        points = self.points if points_rz is None else np.column_stack([points_rz.T, np.zeros(points_rz.shape[1])])
        meshio.write(self.out_dir / fname, meshio.Mesh(points, self.cells, point_data=point_data), binary=True)
        self.frames.append((time_s, fname))
        self._write_pvd()
        return self.out_dir / fname

    def resume(self, frames: list[tuple[float, str]]) -> None:
        """Continue a series whose first ``frames`` were written by an interrupted run: the index is cut back to
        them and later frame files of that run are removed (the resumed run writes them again)."""
        self.frames = list(frames)
        kept = {f for _, f in self.frames}
        for path in self.out_dir.glob(f"{self.name}_[0-9][0-9][0-9][0-9].vtu"):
            if path.name not in kept:
                path.unlink()
        self._write_pvd()

    def _write_pvd(self) -> None:
        lines = ['<?xml version="1.0"?>',
                 '<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">', "  <Collection>"]
        lines += [f'    <DataSet timestep="{t:.6g}" group="" part="0" file={quoteattr(f)}/>' for t, f in self.frames]
        lines += ["  </Collection>", "</VTKFile>", ""]
        tmp = self.out_dir / f"{self.name}.pvd.tmp"
        tmp.write_text("\n".join(lines))
        tmp.replace(self.out_dir / f"{self.name}.pvd")


class ProbeWriter:
    """``probes.csv``: time_s and one temperature column per probe, one row per time step."""

    def __init__(self, path: Path, names: list[str]) -> None:
        self._fh = Path(path).open("w", newline="")
        self._csv = csv.writer(self._fh)
        self._csv.writerow(["time_s", *[f"{n}_C" for n in names]])
        self.names = names

    def write(self, time_s: float, temperatures_C: np.ndarray) -> None:
        self._csv.writerow([f"{time_s:.6g}", *[f"{t:.4f}" for t in temperatures_C]])
        self._fh.flush()

    def close(self) -> None:
        self._fh.close()
