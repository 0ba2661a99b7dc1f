"""Full-chain runs at chosen input factors, cached by a hash of their inputs, run on Dask.

A run is ``(case, inputs, factors)``: the changed data files are written into the run's own folder
(``RUNS/<case>_<hash>/inputs/NAME.toml``, :func:`quenchsim.calibration.inputs.derived_files`) and the case
is pointed at them; the folder name is a hash of the resolved case and the factors, so the same run is
never run twice and an interrupted design is finished by asking for it again (only what is missing runs).
Execution is :func:`quenchsim.sweep.run_on_dask` (a LocalCluster of ``workers`` one-thread processes) or,
with ``workers = 0``, this process.
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from tqdm import tqdm

from quenchsim.calibration.data import quantity
from quenchsim.calibration.inputs import FreeInput, derived_files, used_by
from quenchsim.case import Case
from quenchsim.results import files
from quenchsim.sweep import case_hash, finished, run_on_dask, run_point

__all__ = ["DesignOutcome", "RunRequest", "quantity", "request", "run_requests"]


@dataclass(frozen=True)
class RunRequest:
    """One full-chain run: the case and each input's factor (inputs the case does not read are left out)."""

    case: Case
    inputs: tuple[FreeInput, ...]
    factors: tuple[float, ...]

    def key(self) -> str:
        text = json.dumps([self.case.name, self.case.resolved(), [(i.path, repr(float(f)))
                                                                  for i, f in zip(self.inputs, self.factors)]],
                          sort_keys=True, default=str)
        return hashlib.sha1(text.encode()).hexdigest()[:12]

    def folder_name(self) -> str:
        return f"{self.case.name}_{self.case.condition or 'base'}_{self.key()}"


def request(case: Case, inputs: Sequence[FreeInput], factors: Sequence[float]) -> RunRequest:
    """The run of ``case`` with those inputs it reads set to their factors."""
    chosen = [(i, float(f)) for i, f in zip(inputs, factors) if used_by(i, case)]
    return RunRequest(case=case, inputs=tuple(i for i, _ in chosen), factors=tuple(f for _, f in chosen))


@dataclass
class DesignOutcome:
    """Summaries by folder name (None: failed or not run), and what this call ran; ``failed``: the error of each
    run that failed, by folder name."""

    summaries: dict[str, dict[str, Any] | None]
    ran: int
    cached: int
    failed: dict[str, str]
    pending: list[str]


def _arguments(req: RunRequest, folder: Path) -> tuple[dict[str, Any], str | None, None, dict[str, Any], str]:
    overrides = derived_files(list(req.inputs), list(req.factors), folder / "inputs") if req.inputs else {}
    raw = {**req.case.data, "name": req.case.name}
    return raw, str(req.case.path) if req.case.path else None, None, overrides, str(folder)


def run_requests(requests: Sequence[RunRequest], runs_dir: Path, workers: int = 2, progress: bool = True,
                 max_runs: int | None = None, desc: str = "runs", scheduler: str | None = None) -> DesignOutcome:
    """Run every request not yet finished in ``runs_dir`` (at most ``max_runs`` new ones) and return the
    summaries; failed runs are recorded (their folders keep what they wrote), never raised. ``scheduler``: the
    address of a running Dask scheduler (a cluster kept over many calls) instead of a LocalCluster per call."""
    runs_dir.mkdir(parents=True, exist_ok=True)
    unique: dict[str, RunRequest] = {}
    for req in requests:
        unique.setdefault(req.folder_name(), req)
    summaries: dict[str, dict[str, Any] | None] = {}
    todo: dict[str, tuple[Any, ...]] = {}
    for name, req in unique.items():
        args = _arguments(req, runs_dir / name)
        done = finished(Path(args[4]), case_hash(args[0], None, args[3]))
        if done is not None:
            summaries[name] = done
        else:
            todo[name] = args
    cached = len(summaries)
    names = list(todo)
    pending = names[max_runs:] if max_runs is not None else []
    todo = {n: todo[n] for n in names if n not in pending}
    failed: dict[str, str] = {}
    bar = tqdm(total=len(unique) - len(pending), initial=cached, desc=desc, unit="run", disable=not progress)

    def record(name: str, result: Mapping[str, Any]) -> None:
        ok = result["status"] in files.FINISHED_STATUSES   # a hot part's results are kept (its status says so)
        summaries[name] = result["summary"] if ok else None
        if not ok:
            failed[name] = str(result.get("error") or result["status"])
        bar.update(1)
        bar.set_postfix_str(f"{len(failed)} failed" if failed else "")

    try:
        if workers == 0 and not scheduler:
            for name, args in todo.items():
                record(name, run_point(*args))
        elif todo and run_on_dask(todo, scheduler, workers, record):
            raise KeyboardInterrupt
    finally:
        bar.close()
    for name in pending:
        summaries[name] = None
    return DesignOutcome(summaries=summaries, ran=len(todo), cached=cached, failed=failed, pending=pending)

