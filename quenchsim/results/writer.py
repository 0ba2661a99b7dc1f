"""Writing a run folder: every file of the output contract, each as soon as it is known.

The VTK series and the probe CSV are flushed after every write, and ``summary.json`` is replaced
atomically, so a run that stops keeps everything up to its last step (see :mod:`quenchsim.results.files`).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np
import tomli_w

from quenchsim.errors import InputError
from quenchsim.io import ProbeWriter, VtkSeries
from quenchsim.io.revolve import revolve_vtu
from quenchsim.results import files


def claim_run_folder(out_dir: str | Path, force: bool = False) -> None:
    """Make ``out_dir`` ready for a new (not resumed) run, before anything is written: a missing or empty folder
    is used as it is; a quenchsim run folder (:data:`files.RUN_MARKERS`) loses its earlier run's outputs
    (:data:`files.RUN_OUTPUTS`); any other non-empty folder is refused (a one-line :class:`InputError`) unless
    ``force``, which writes the run into it and removes nothing else."""
    out = Path(out_dir)
    if not out.is_dir() or not any(out.iterdir()):
        if out.exists() and not out.is_dir():
            raise InputError("out", str(out), "is a file, not a folder; choose a folder for the run")
        return
    if not force and not any((out / name).exists() for name in files.RUN_MARKERS):
        raise InputError("out", str(out), "is a non-empty folder that is not a quenchsim run (no "
                         f"{files.CASE_TOML}); choose a new or empty folder, or pass --force to write into it")
    for pattern in files.RUN_OUTPUTS:
        for path in out.glob(pattern):
            if path.is_file():
                path.unlink()


class RunWriter:
    """The writer of one run folder (created if missing)."""

    def __init__(self, out_dir: str | Path) -> None:
        self.out = Path(out_dir)
        try:
            self.out.mkdir(parents=True, exist_ok=True)
            probe = self.out / ".quenchsim_write_test"
            probe.write_text("")
            probe.unlink()
        except OSError as exc:
            raise InputError("out", str(self.out), f"cannot be written: {exc.strerror or exc}") from None

    @property
    def mesh_path(self) -> Path:
        return self.out / files.MESH_MSH

    def case(self, resolved: dict[str, Any]) -> None:
        (self.out / files.CASE_TOML).write_text(tomli_w.dumps(resolved))

    def series(self, points_rz: np.ndarray, triangles: np.ndarray) -> VtkSeries:
        return VtkSeries(self.out, points_rz, triangles, name=files.SERIES_NAME)

    def probes(self, names: list[str]) -> ProbeWriter:
        return ProbeWriter(self.out / files.PROBES_CSV, names)

    def final_3d(self, last_vtu: Path) -> None:
        revolve_vtu(last_vtu, self.out / files.FINAL_3D_VTU)

    def hardness_traverse(self, depth_mm: np.ndarray, hrc_from_bore: np.ndarray, hrc_from_od: np.ndarray,
                          prefix: str = "") -> None:
        _csv(self.out / (prefix + files.HARDNESS_TRAVERSE_CSV), "depth_mm,HRC_from_bore,HRC_from_od",
             np.column_stack([depth_mm, hrc_from_bore, hrc_from_od]), "%.5g")

    def residual_traverse(self, r_mm: np.ndarray, hoop_MPa: np.ndarray, axial_MPa: np.ndarray,
                          prefix: str = "") -> None:
        _csv(self.out / (prefix + files.RESIDUAL_TRAVERSE_CSV), "r_mm,hoop_MPa,axial_MPa", np.column_stack([r_mm, hoop_MPa, axial_MPa]),
             "%.6g")

    def outline(self, before_mm: np.ndarray, after_mm: np.ndarray, prefix: str = "") -> None:
        _csv(self.out / (prefix + files.OUTLINE_CSV), "r_before_mm,z_before_mm,r_after_mm,z_after_mm",
             np.column_stack([before_mm, after_mm]), "%.6f")

    def summary(self, summary: dict[str, Any]) -> None:
        """Write ``summary.json`` atomically (a reader never sees half a file)."""
        tmp = self.out / (files.SUMMARY_JSON + ".tmp")
        tmp.write_text(json.dumps(summary, indent=2))
        tmp.replace(self.out / files.SUMMARY_JSON)


def _csv(path: Path, header: str, columns: np.ndarray, fmt: str) -> None:
    np.savetxt(path, columns, delimiter=",", header=header, comments="", fmt=fmt)
