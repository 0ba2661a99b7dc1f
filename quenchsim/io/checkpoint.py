"""Checkpoints: the whole state of a run as named arrays plus a JSON header in one ``.npz`` file.

A state is a nested mapping whose leaves are arrays, numbers, booleans or ``None``; :func:`write_checkpoint`
flattens it to ``a/b/c`` keys and replaces the file atomically (written to a temporary file, then renamed), so
a run stopped while it writes keeps the previous checkpoint whole. Leaves may also be sparse matrices (the
factorised step matrices a solver keeps, so a resumed run repeats the same iterations); they come back as CSR.
"""

from __future__ import annotations

import json
import os
import time
import zipfile
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import scipy.sparse as sp

from quenchsim.errors import InputError
from quenchsim.run_state import Position, RunState, StepCounts

FORMAT_VERSION = 3
"""Written into every checkpoint; a file of another version is not resumed. 2: the stress solver's state since
its last step (multirate stress steps) and the CG iterations since its last factorisation were added. 3: the
thermal solver's last step (BDF2 history)."""
_HEADER = "__header__"
_NONE = "__none__"
_CSR = "__csr__"


def write_checkpoint(path: str | Path, state: Mapping[str, Any], header: Mapping[str, Any]) -> Path:
    """Write ``state`` (nested mapping of arrays) and ``header`` (JSON-serialisable) to ``path`` atomically."""
    path = Path(path)
    arrays: dict[str, Any] = _flatten(state, "")   # Any: numpy's savez stub types **kwds against allow_pickle
    arrays[_HEADER] = np.array(json.dumps({"format": FORMAT_VERSION, **header}))
    tmp = path.with_name(path.name + ".tmp")
    with tmp.open("wb") as fh:
        np.savez(fh, **arrays)
        fh.flush()
        os.fsync(fh.fileno())
    tmp.replace(path)
    return path


def read_checkpoint(path: str | Path) -> tuple[dict[str, Any], dict[str, Any]]:
    """``(header, state)`` of a checkpoint written by :func:`write_checkpoint` (state nested as written)."""
    with np.load(Path(path), allow_pickle=False) as data:
        header = json.loads(str(data[_HEADER]))
        state: dict[str, Any] = {}
        for key in data.files:
            if key == _HEADER:
                continue
            *parents, leaf = key.split("/")
            node = state
            for name in parents:
                node = node.setdefault(name, {})
            value = data[key]
            node[leaf] = None if value.dtype.kind == "U" and str(value) == _NONE else value
    return header, _with_matrices(state)


def _flatten(state: Mapping[str, Any], prefix: str) -> dict[str, np.ndarray]:
    out: dict[str, np.ndarray] = {}
    for key, value in state.items():
        name = f"{prefix}{key}"
        if sp.issparse(value):
            csr = sp.csr_matrix(value)
            out.update(_flatten({_CSR: {"data": csr.data, "indices": csr.indices, "indptr": csr.indptr,
                                        "shape": np.array(csr.shape)}}, name + "/"))
        elif isinstance(value, Mapping):
            out.update(_flatten(value, name + "/"))
        else:
            out[name] = np.array(_NONE) if value is None else np.asarray(value)
    return out


def _with_matrices(state: dict[str, Any]) -> dict[str, Any]:
    for key, value in state.items():
        if isinstance(value, dict):
            if _CSR in value:
                m = value[_CSR]
                shape = tuple(int(n) for n in m["shape"])
                state[key] = sp.csr_matrix((m["data"], m["indices"], m["indptr"]), shape=shape)
            else:
                _with_matrices(value)
    return state


def read_resumable(path: Path, resolved: dict[str, Any], out_dir: Path) -> tuple[dict[str, Any], dict[str, Any]]:
    """The checkpoint ``path`` of the run folder ``out_dir`` when it belongs to the case ``resolved`` (the same
    resolved inputs); otherwise a one-line :class:`InputError` (no checkpoint, another case, another checkpoint
    format)."""
    if not path.is_file():
        raise InputError("--resume", str(out_dir), f"holds no {path.name} to continue from (the run "
                         "completed, or never reached its first checkpoint); run without --resume")
    try:
        header, state = read_checkpoint(path)
    except (OSError, ValueError, KeyError, zipfile.BadZipFile) as exc:
        raise InputError("--resume", str(path), f"cannot be read ({exc}); run without --resume") from None
    if header.get("format") != FORMAT_VERSION:
        raise InputError("--resume", str(path), f"is of checkpoint format {header.get('format')}, this version "
                         f"reads {FORMAT_VERSION}; run without --resume")
    difference = _first_difference(_results_inputs(header["case"]), _results_inputs(resolved))
    if difference is not None:
        raise InputError("--resume", str(out_dir), f"its run is of another case ({difference}); resume with the "
                         "same case file, condition and --set options, or run without --resume")
    return header, state


def _results_inputs(resolved: dict[str, Any]) -> dict[str, Any]:
    """A resolved case as JSON data without the options that change no result (how often to checkpoint)."""
    data = json.loads(json.dumps(resolved))
    data.get("output", {}).pop("checkpoint_minutes", None)
    return data


def _first_difference(there: Any, here: Any, key: str = "") -> str | None:
    """The first dotted key where two resolved cases differ, as ``key: A there, B here``."""
    if isinstance(there, dict) and isinstance(here, dict):
        for k in sorted(set(there) | set(here)):
            found = _first_difference(there.get(k), here.get(k), f"{key}.{k}" if key else k)
            if found:
                return found
        return None
    return None if there == here else f"{key}: {there!r} there, {here!r} here"


def save_run(run: RunState) -> None:
    """Write the whole state of ``run`` (:class:`quenchsim.pipeline.QuenchRun`) after its last committed step to its
    checkpoint file (atomically): solvers, phases, stresses, the record so far, position, counts and timings."""
    state = {"thermal": run.thermal.checkpoint_state(),
             "phases": run.phase_model.checkpoint_state(run.thermal.phase_state),
             "run": {**run.record.checkpoint_state(), "mesh_p": run.section.mesh.p}}
    if run.stress is not None:
        state.update(run.stress.checkpoint_state())
    header = {"case": run.case.resolved(), "position": run.position.as_dict(), "counts": run.counts.as_dict(),
              "frames": run.record.vtk.frames, "wall_time_s": time.perf_counter() - run.wall0,
              "timings_s": run.timings, "time_s": run.thermal.time_s}
    write_checkpoint(run.checkpoint_path, state, header)


@dataclass(frozen=True)
class Restored:
    """What a checkpoint gives back to the run beside its solvers' state: its counters and position, the record's
    arrays, the frames written and the wall time so far (s)."""

    counts: StepCounts
    position: Position
    record: dict[str, Any]
    frames: list[tuple[Any, ...]]
    wall_time_s: float


def restore_run(run: RunState, header: dict[str, Any], state: dict[str, Any]) -> Restored:
    """Put a checkpoint's state into the freshly built solvers of ``run``; returns the rest for the run to take
    (:class:`Restored`)."""
    mesh_p = state["run"]["mesh_p"]
    p = run.section.mesh.p
    if mesh_p.shape != p.shape or not np.allclose(mesh_p, p, rtol=0.0, atol=1e-12):
        raise InputError("--resume", str(run.checkpoint_path), "the checkpoint's mesh differs from the one "
                         "built now (another gmsh version?); run without --resume")
    run.thermal.restore_state(state["thermal"], run.phase_model.restore_state(state["phases"]))
    if run.stress is not None:
        run.stress.restore_state(state)
    run.timings.update(header["timings_s"])
    return Restored(StepCounts.from_dict(header["counts"]), Position.from_dict(header["position"]), state["run"],
                    [tuple(f) for f in header["frames"]], float(header["wall_time_s"]))
