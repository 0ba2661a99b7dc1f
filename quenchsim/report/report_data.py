"""Reading a run directory (the `quenchsim run` output contract) or a sweep directory for the reports.

Everything is optional: a run that stopped early, or an older run without the mechanics files, gives
``None`` for what it lacks (the report lists what is missing).
"""

from __future__ import annotations

import json
import tomllib
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from quenchsim.errors import InputError

PHASES = ("austenite", "pearlite", "bainite", "martensite")


def last_frame(run_dir: Path) -> Path | None:
    """The last ``.vtu`` of a run: the last entry of ``results.pvd``, else the highest-numbered file."""
    pvd = run_dir / "results.pvd"
    if pvd.is_file():
        try:
            files = [ds.get("file") for ds in ET.parse(pvd).getroot().iter("DataSet")]
        except ET.ParseError:
            files = []
        files = [run_dir / f for f in files if f and (run_dir / f).is_file()]
        if files:
            return files[-1]
    frames = sorted(run_dir.glob("results_*.vtu"))
    return frames[-1] if frames else None


def _csv(path: Path) -> dict[str, np.ndarray] | None:
    if not path.is_file():
        return None
    data = np.genfromtxt(path, delimiter=",", names=True, ndmin=1)
    if data.size == 0:
        return None
    return {name: np.atleast_1d(data[name]).astype(float) for name in data.dtype.names}


@dataclass
class Frame:
    """The last VTK frame: points (x = r, y = z in m), triangles and point data."""

    path: Path
    points: np.ndarray
    triangles: np.ndarray
    point_data: dict[str, np.ndarray]


@dataclass
class RunData:
    """What a run directory holds (each part None when absent)."""

    path: Path
    case: dict[str, Any] | None
    summary: dict[str, Any] | None
    probes: dict[str, np.ndarray] | None
    frame: Frame | None
    hardness_traverse: dict[str, np.ndarray] | None
    hoop_traverse: dict[str, np.ndarray] | None
    outline: dict[str, np.ndarray] | None
    notes: list[str] = field(default_factory=list)

    @property
    def title(self) -> str:
        name = (self.summary or {}).get("case") or (self.case or {}).get("name") or self.path.name
        condition = (self.summary or {}).get("condition") or (self.case or {}).get("condition")
        return f"{name}, condition {condition}" if condition not in (None, "") else str(name)


def load_frame(path: Path) -> Frame:
    import meshio

    mesh = meshio.read(path)
    triangles = np.concatenate([c.data for c in mesh.cells if c.type == "triangle"]) if mesh.cells else np.zeros((0, 3))
    return Frame(path=path, points=np.asarray(mesh.points), triangles=np.asarray(triangles, dtype=int),
                 point_data={k: np.asarray(v) for k, v in mesh.point_data.items()})


def load_run(run_dir: str | Path) -> RunData:
    """Read what there is of a run directory."""
    path = Path(run_dir)
    if not path.is_dir():
        raise InputError("RUN_DIR", str(path), "is not a directory")
    notes: list[str] = []
    case = summary = None
    if (path / "case.toml").is_file():
        try:
            case = tomllib.loads((path / "case.toml").read_text())
        except tomllib.TOMLDecodeError as exc:
            notes.append(f"case.toml is not valid TOML ({exc})")
    if (path / "summary.json").is_file():
        try:
            summary = json.loads((path / "summary.json").read_text())
        except ValueError as exc:
            notes.append(f"summary.json is not valid JSON ({exc})")
    frame_path = last_frame(path)
    frame = None
    if frame_path is not None:
        try:
            frame = load_frame(frame_path)
        except Exception as exc:  # noqa: BLE001 -- a damaged frame is reported, the rest still shown
            notes.append(f"{frame_path.name} could not be read ({type(exc).__name__}: {exc})")
    probes = _csv(path / "probes.csv")
    if probes is not None and len(probes.get("time_s", ())) < 2:
        probes = None
    return RunData(path=path, case=case, summary=summary, probes=probes, frame=frame,
                   hardness_traverse=_csv(path / "hardness_traverse.csv"),
                   hoop_traverse=_csv(path / "residual_hoop_traverse.csv"), outline=_csv(path / "outline.csv"),
                   notes=notes)


def is_sweep_dir(path: Path) -> bool:
    """A sweep output directory: results.csv plus sweep.json (written by quenchsim.sweep)."""
    return (path / "results.csv").is_file() and (path / "sweep.json").is_file()


def measured_dimensions(case: dict[str, Any] | None) -> dict[str, dict[str, float]]:
    """``{"before": {...}, "after": {...}, "change": {...}}`` from the case's ``[measured]`` table (mm)."""
    measured = (case or {}).get("measured", {})
    before = {k: float(v) for k, v in measured.get("before_mm", {}).items() if isinstance(v, (int, float))}
    after = {k: float(v) for k, v in measured.get("after_mm", {}).items() if isinstance(v, (int, float))}
    change = {k: after[k] - before[k] for k in after if k in before}
    return {"before": before, "after": after, "change": change}
