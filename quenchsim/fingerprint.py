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


RUN_MODULES = ("quenchsim.pipeline", "quenchsim.sweep")
"""What executes a run (the staged run and the sweep's run of one case): :func:`run_fingerprint` covers their
import closure (:mod:`quenchsim.dependencies`), not the calibration, report or command code around them."""


def run_fingerprint() -> str:
    """Like :func:`code_fingerprint`, but over only the modules a run executes (the import closure of
    :data:`RUN_MODULES`, with the data files that travel with them) and the data folders: a cached run (a sweep's,
    a calibration's or an uncertainty draw's case, keyed by :func:`quenchsim.sweep.case_hash`) stays valid while
    the code around the runs -- a calibration's statistics, a report's page -- changes."""
    shipped = materials_dir()
    return _fingerprint(tuple(f.resolve() for f in data_folders() if f != shipped), shipped.resolve(), runs_only=True)


def _run_files(package: Path) -> list[Path]:
    from quenchsim.dependencies import code_closure, package_data

    closure = code_closure([f"import {m}" for m in RUN_MODULES], package.parent)
    return sorted({*closure.modules.values(), *package_data(closure)})


@functools.lru_cache(maxsize=8)
def _fingerprint(user_folders: tuple[Path, ...], shipped: Path, runs_only: bool = False,
                 package: Path = Path(__file__).resolve().parent) -> str:
    digest = hashlib.sha1()
    folders = [(package, "quenchsim"), (shipped, "materials"), *((f, f"data/{f.as_posix()}") for f in user_folders)]
    for folder, name in folders:
        paths = _run_files(package) if runs_only and folder == package else sorted(folder.rglob("*"))
        for path in paths:
            if path.suffix in (".py", ".toml") and "__pycache__" not in path.parts:
                digest.update(f"{name}/{path.relative_to(folder).as_posix()}".encode())
                digest.update(behaviour_bytes(path))
    return digest.hexdigest()
