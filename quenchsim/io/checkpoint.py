"""Checkpoints: the whole state of a run as named arrays plus a JSON header in one ``.npz`` file.

A state is a nested mapping whose leaves are arrays, numbers, booleans or ``None``; :func:`write_checkpoint`
flattens it to ``a/b/c`` keys and replaces the file atomically (written to a temporary file, then renamed), so
a run stopped while it writes keeps the previous checkpoint whole. Leaves may also be sparse matrices (the
factorised step matrices a solver keeps, so a resumed run repeats the same iterations); they come back as CSR.
"""

from __future__ import annotations

import json
import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np
import scipy.sparse as sp

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
    arrays = _flatten(state, "")
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
