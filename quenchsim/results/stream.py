"""What a run writes as it goes: the probe temperatures after every committed step (probes.csv) and a VTK frame
per 1/frames of the whole cooling, so a run that stops keeps what it had computed."""

from __future__ import annotations

from typing import Any

import numpy as np


class RunRecord:
    """The probe rows and VTK frames of a run written by ``writer`` (:class:`quenchsim.results.RunWriter`) on
    ``mesh``: probes ``names`` read by ``matrix`` from the nodal temperatures (None: no probes), a frame whenever the
    mean nodal change since the last one reaches ``frame_dT_K`` (the max-norm counted the fast surface swings:
    ~260 frames for 40 requested)."""

    def __init__(self, writer: Any, mesh: Any, names: list[str], matrix: Any, frame_dT_K: float) -> None:
        self.vtk = writer.series(mesh.p, mesh.t)
        self.probes = writer.probes(names)
        self.names, self.matrix, self.frame_dT_K = names, matrix, frame_dT_K
        self.times: list[float] = []
        self.rows: list[np.ndarray] = []
        self.last_frame_T: np.ndarray | None = None

    def temperatures(self, T: np.ndarray) -> np.ndarray:
        """The probe temperatures of the nodal temperatures ``T``."""
        return self.matrix @ T if self.matrix is not None else np.zeros(0)

    def start(self, T: np.ndarray, fields: dict[str, np.ndarray]) -> None:
        """The first row and frame, at t = 0."""
        self.times, self.rows = [0.0], [self.temperatures(T)]
        self.probes.write(0.0, self.rows[0])
        self.vtk.write(0.0, fields)
        self.last_frame_T = T.copy()

    def resume(self, arrays: dict[str, Any], frames: list[tuple[Any, ...]]) -> None:
        """The rows and frames up to a checkpoint (``arrays``: :meth:`checkpoint_state`), as the run wrote them."""
        self.times = [float(t) for t in arrays["times"]]
        self.rows = list(np.asarray(arrays["probe_rows"]).reshape(len(self.times), -1))
        self.last_frame_T = np.array(arrays["last_frame_T"])
        for t, row in zip(self.times, self.rows):
            self.probes.write(t, row)
        self.vtk.resume(frames)

    def step(self, time_s: float, T: np.ndarray) -> None:
        """The row of a committed step."""
        self.times.append(time_s)
        self.rows.append(self.temperatures(T))
        self.probes.write(time_s, self.rows[-1])

    def frame_due(self, T: np.ndarray) -> bool:
        """Whether the nodal temperatures ``T`` have moved a frame's worth since the last frame."""
        return float(np.mean(np.abs(T - self.last_frame_T))) >= self.frame_dT_K

    def frame(self, time_s: float, T: np.ndarray, fields: dict[str, np.ndarray]) -> None:
        self.vtk.write(time_s, fields)
        self.last_frame_T = T.copy()

    def checkpoint_state(self) -> dict[str, Any]:
        return {"times": np.asarray(self.times), "probe_rows": np.asarray(self.rows), "last_frame_T": self.last_frame_T}

    def series(self) -> tuple[np.ndarray, dict[str, np.ndarray]]:
        """The step-end times and each probe's temperatures at them."""
        return (np.asarray(self.times),
                {n: np.array([row[i] for row in self.rows]) for i, n in enumerate(self.names)})
