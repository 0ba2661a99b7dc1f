"""Reading a run folder back: the one reader the report, the sweep and users' scripts share.

``quenchsim.results.load(DIR)`` returns a :class:`RunResults`; everything is optional, so a run that
stopped early, or an older run without the mechanics files, gives ``None`` for what it lacks.
"""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from quenchsim.errors import InputError
from quenchsim.inputs.reader import read_toml
from quenchsim.results import files


def read_summary(run_dir: str | Path) -> dict[str, Any] | None:
    """A run folder's ``summary.json`` (None when it is missing or not valid JSON: a run still going, or killed
    while the file was replaced)."""
    try:
        return json.loads((Path(run_dir) / files.SUMMARY_JSON).read_text())
    except (OSError, ValueError):
        return None


def last_frame(run_dir: Path) -> Path | None:
    """The last ``.vtu`` of a run: the last entry of ``results.pvd``, else the highest-numbered file."""
    pvd = run_dir / files.SERIES_PVD
    if pvd.is_file():
        try:
            listed = [ds.get("file") for ds in ET.parse(pvd).getroot().iter("DataSet")]
        except ET.ParseError:
            listed = []
        frames = [run_dir / f for f in listed if f and (run_dir / f).is_file()]
        if frames:
            return frames[-1]
    frames = sorted(run_dir.glob(f"{files.SERIES_NAME}_*.vtu"))
    return frames[-1] if frames else None


def _csv(path: Path) -> dict[str, np.ndarray] | None:
    if not path.is_file():
        return None
    data = np.genfromtxt(path, delimiter=",", names=True, ndmin=1)
    if data.size == 0:
        return None
    names = data.dtype.names
    assert names is not None   # names=True gives a structured array
    return {name: np.atleast_1d(data[name]).astype(float) for name in names}


@dataclass
class Frame:
    """The last VTK frame: points (x = r, y = z in m), triangles and point data."""

    path: Path
    points: np.ndarray
    triangles: np.ndarray
    point_data: dict[str, np.ndarray]


@dataclass
class RunResults:
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


def load(run_dir: str | Path) -> RunResults:
    """Read what there is of a run folder; parts it lacks are None and ``notes`` says what could not be read."""
    path = Path(run_dir)
    if not path.is_dir():
        raise InputError("RUN_DIR", str(path), "is not a directory")
    notes: list[str] = []
    case = summary = None
    if (path / files.CASE_TOML).is_file():
        try:
            case = read_toml(path / files.CASE_TOML, files.CASE_TOML)
        except InputError as exc:
            notes.append(f"{files.CASE_TOML} {exc.allowed}")
    if (path / files.SUMMARY_JSON).is_file():
        try:
            summary = json.loads((path / files.SUMMARY_JSON).read_text())
        except ValueError as exc:
            notes.append(f"{files.SUMMARY_JSON} is not valid JSON ({exc})")
    frame_path = last_frame(path)
    frame = None
    if frame_path is not None:
        try:
            frame = load_frame(frame_path)
        except Exception as exc:  # noqa: BLE001 -- a damaged frame is reported, the rest still shown
            notes.append(f"{frame_path.name} could not be read ({type(exc).__name__}: {exc})")
    probes = _csv(path / files.PROBES_CSV)
    if probes is not None and len(probes.get("time_s", ())) < 2:
        probes = None
    return RunResults(path=path, case=case, summary=summary, probes=probes, frame=frame,
                   hardness_traverse=_csv(path / files.HARDNESS_TRAVERSE_CSV),
                   hoop_traverse=_csv(path / files.RESIDUAL_TRAVERSE_CSV), outline=_csv(path / files.OUTLINE_CSV),
                   notes=notes)
