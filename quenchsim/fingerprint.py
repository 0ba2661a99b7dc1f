"""The fingerprint of the code and data that produce a run: a cached result (a validation study's run, a sweep's
or a calibration's case) is reused only while its inputs and this fingerprint are unchanged."""

from __future__ import annotations

import functools
import hashlib
from pathlib import Path

from quenchsim.behaviour import behaviour_bytes
from quenchsim.materials import data_folders, materials_dir


def code_fingerprint() -> str:
    """SHA-1 over every source and data file (``.py``, ``.toml``) of the package, of the shipped materials folder
    and of the user's data folders on the search path (:func:`quenchsim.materials.data_folders`: a re-fitted oil of
    the user's invalidates the runs that used it), by their paths as ``quenchsim/...``, ``materials/...`` and
    ``data/<folder>/...`` (so the same checkout gives the same value wherever it lies); a module counts by what it
    computes (:func:`quenchsim.behaviour.behaviour_bytes`: comments, docstrings and type hints left out).
    Inside :func:`quenchsim.materials.shipped_data_only` (the validation studies) the user's folders are not part
    of it. Computed once per process and search path."""
    shipped = materials_dir()
    return _fingerprint(tuple(f.resolve() for f in data_folders() if f != shipped), shipped.resolve())


@functools.lru_cache(maxsize=4)
def _fingerprint(user_folders: tuple[Path, ...], shipped: Path) -> str:
    digest = hashlib.sha1()
    folders = [(Path(__file__).resolve().parent, "quenchsim"), (shipped, "materials"),
               *((f, f"data/{f.as_posix()}") for f in user_folders)]
    for folder, name in folders:
        for path in sorted(folder.rglob("*")):
            if path.suffix in (".py", ".toml") and "__pycache__" not in path.parts:
                digest.update(f"{name}/{path.relative_to(folder).as_posix()}".encode())
                digest.update(behaviour_bytes(path))
    return digest.hexdigest()
