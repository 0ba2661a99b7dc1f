"""The fingerprint of the code and data that produce a run: a cached result (a validation study's run, a sweep's
or a calibration's case) is reused only while its inputs and this fingerprint are unchanged."""

from __future__ import annotations

import functools
import hashlib
from pathlib import Path

from quenchsim.materials import materials_dir


@functools.lru_cache(maxsize=1)
def code_fingerprint() -> str:
    """SHA-1 over every source and data file (``.py``, ``.toml``) of the package and of the materials folder, by
    their paths as ``quenchsim/...`` and ``materials/...`` (so the same checkout gives the same value wherever it
    lies). Computed once per process."""
    digest = hashlib.sha1()
    for folder, name in ((Path(__file__).resolve().parent, "quenchsim"), (materials_dir(), "materials")):
        for path in sorted(folder.rglob("*")):
            if path.suffix in (".py", ".toml") and "__pycache__" not in path.parts:
                digest.update(f"{name}/{path.relative_to(folder).as_posix()}".encode())
                digest.update(path.read_bytes())
    return digest.hexdigest()
