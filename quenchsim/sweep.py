"""Parameter sweeps: a base case plus grids or lists of any dotted case field, run on Dask distributed.

A sweep file (TOML)::

    [sweep]
    case = "crb_outer_ring.toml"     # base case, relative to the sweep file
    condition = "1"                  # named condition of the base case (if it has conditions)

    [set]                            # fixed overrides applied to every case (nested tables or
    mesh.size_mm = 12.0              # quoted dotted keys; each leaf is one case field)

    [grid]                           # Cartesian product of every list
    quench.bath.id_jet_speed_mm_s = [400.0, 1000.0, 2000.0]
    quench.bath.od_jet_speed_mm_s = [1780.0, 5340.0]

    [zip]                            # lists of equal length varied together (combined with [grid])
    process.austenitising_temperature_C = [830.0, 845.0]
    quench.time_s = [600.0, 900.0]

Each case runs in ``OUT/<name from the parameter values>/`` (the ``quenchsim run`` output contract,
plus ``sweep_case.json`` with the inputs of the case). ``OUT/results.csv`` has one row per finished
case -- status (ok / failed), error, the swept inputs, the key outputs of ``summary.json`` flattened
to dotted column names -- and is rewritten atomically after every case. A case whose folder holds a
``summary.json`` with status ok and the same inputs is not run again, so an interrupted sweep
(Ctrl-C, a killed process or a lost worker) is finished by running the same command again.

Execution: Dask distributed -- a ``LocalCluster`` (``workers`` processes, one thread each) or an
existing scheduler by address; ``workers=0`` runs the cases one after another in this process
(the serial reference of the speed-up measurement, and for debugging). The base case table is sent
to the workers, but each worker writes its case folder itself: with workers on other machines the
output directory must be on a file system they share (the same absolute path everywhere), and they
need the same quenchsim installed.
"""

from __future__ import annotations

import csv
import ctypes
import ctypes.util
import hashlib
import itertools
import json
import logging
import re
import time
import traceback
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Iterator, Mapping

from tqdm import tqdm

from quenchsim.case import case_from_dict
from quenchsim.errors import InputError, require
from quenchsim.inputs.declare import from_table
from quenchsim.inputs.reader import read_toml, reading
from quenchsim.inputs.sweep import SweepFile
from quenchsim.fingerprint import run_fingerprint
from quenchsim.results import RunWriter, files, read_summary

RESULTS_CSV = "results.csv"
SWEEP_JSON = "sweep.json"
CASE_JSON = "sweep_case.json"
KEY_OUTPUTS = ("probes", "hardness", "phases_final", "dimensions_mm", "shape_mm", "residual_stress_MPa", "solver")
"""Top-level tables of summary.json whose numeric leaves become result columns."""
SOLVER_KEYS = ("wall_time_s", "steps", "dofs")
log = logging.getLogger("quenchsim")


@dataclass
class SweepSpec:
    """A parsed sweep: base case, fixed overrides and one dict of dotted parameter values per case."""

    name: str
    case_path: Path | None
    condition: str | None
    fixed: dict[str, Any]
    parameters: list[str]
    points: list[dict[str, Any]]
    raw_case: dict[str, Any] = field(repr=False, default_factory=dict)

    def overrides(self, point: dict[str, Any]) -> dict[str, Any]:
        """Every dotted override of one case: the fixed ones, then the case's parameter values."""
        return {**self.fixed, **point}


@dataclass
class SweepOutcome:
    """What a call of :func:`run_sweep` did."""

    out_dir: Path
    rows: list[dict[str, Any]]
    skipped: int
    ran: int
    failed: int
    pending: int
    wall_time_s: float
    interrupted: bool = False

    def as_dict(self) -> dict[str, Any]:
        return {"out": str(self.out_dir), "cases": len(self.rows) + self.pending, "skipped": self.skipped,
                "ran": self.ran, "failed": self.failed, "pending": self.pending,
                "wall_time_s": round(self.wall_time_s, 3), "interrupted": self.interrupted,
                "results": str(self.out_dir / RESULTS_CSV)}


def flatten(table: dict[str, Any], prefix: str = "") -> Iterator[tuple[str, Any]]:
    """Leaves of nested tables as ``(dotted key, value)``; quoted dotted keys pass through unchanged."""
    for key, value in table.items():
        dotted = f"{prefix}{key}"
        if isinstance(value, dict):
            yield from flatten(value, dotted + ".")
        else:
            yield dotted, value


def _has_parent(data: Mapping[str, Any], dotted: str) -> bool:
    node: Any = data
    for key in dotted.split(".")[:-1]:
        if not isinstance(node, dict) or key not in node:
            return False
        node = node[key]
    return isinstance(node, dict)


def parse_sweep(raw: dict[str, Any], base_dir: Path, name: str = "sweep") -> SweepSpec:
    """Build a :class:`SweepSpec` from a sweep table (as read from TOML, :class:`quenchsim.inputs.sweep.SweepFile`);
    errors name the field."""
    spec = from_table(SweepFile, raw)
    head = spec.sweep
    case_path = (base_dir / head.case).resolve()
    require(case_path.is_file(), "sweep.case", head.case, f"file not found ({case_path})")
    raw_case = read_toml(case_path, "sweep.case")
    return make_sweep(raw_case, grid=dict(spec.grid), zipped=dict(spec.zip), fixed=dict(spec.set),
                      condition=None if head.condition is None else str(head.condition), case_path=case_path,
                      name=head.name if head.name is not None else name)


def make_sweep(raw_case: dict[str, Any], grid: dict[str, Any] | None = None, zipped: dict[str, Any] | None = None,
               fixed: dict[str, Any] | None = None, condition: str | None = None, case_path: Path | None = None,
               name: str = "sweep") -> SweepSpec:
    """A sweep of a case table (e.g. built in a script): ``grid`` lists form a Cartesian product,
    ``zipped`` lists vary together, ``fixed`` applies to every case; keys are dotted case fields
    (or nested tables of them). The base case with the fixed overrides is validated here."""
    fixed_flat = dict(flatten(fixed or {}))
    grid_flat = dict(flatten(grid or {}))
    zip_flat = dict(flatten(zipped or {}))
    for table, values in (("grid", grid_flat), ("zip", zip_flat)):
        for key, v in values.items():
            require(isinstance(v, list) and len(v) > 0, f"{table}.{key}", v, "must be a non-empty list of values")
    lengths = {len(v) for v in zip_flat.values()}
    require(len(lengths) <= 1, "zip", {k: len(v) for k, v in zip_flat.items()}, "lists must have equal lengths")
    parameters = [*grid_flat, *zip_flat]
    require(len(parameters) > 0, "grid", None, "a sweep needs at least one list in [grid] or [zip]")
    clash = (set(grid_flat) & set(zip_flat)) | (set(parameters) & set(fixed_flat))
    require(not clash, "sweep parameters", sorted(clash), "a field may appear in only one of [set], [grid], [zip]")
    # the base case with the fixed overrides must be valid on its own: a typo fails before any run
    base = case_from_dict(raw_case, condition, fixed_flat, path=case_path)
    for key in parameters:
        require(_has_parent(base.data, key), key, (grid_flat | zip_flat)[key],
                "is not a field of the case (its parent table does not exist)")
    zip_rows = [dict(zip(zip_flat, values)) for values in zip(*zip_flat.values())] or [{}]
    points = [{**dict(zip(grid_flat, combo)), **z} for combo in itertools.product(*grid_flat.values())
              for z in zip_rows]
    for case_name, point in zip(case_names(parameters, points), points):   # every case is checked before any runs
        try:
            base.with_overrides(point)
        except InputError as exc:
            raise InputError(f"sweep case {case_name}: {exc.field}", exc.value, exc.allowed) from None
    return SweepSpec(name=name, case_path=case_path, condition=condition, fixed=fixed_flat,
                     parameters=parameters, points=points, raw_case=raw_case)


def load_sweep(path: str | Path) -> SweepSpec:
    """Read a sweep file (see the module docstring)."""
    path = Path(path)
    raw = read_toml(path, "sweep")
    with reading(path):
        return parse_sweep(raw, path.parent, name=path.stem)


def _format_value(value: Any) -> str:
    if isinstance(value, float):
        return format(value, ".6g")
    return str(value)


def case_names(parameters: list[str], points: list[dict[str, Any]]) -> list[str]:
    """Folder names from the parameter values, e.g. ``id_jet_speed_mm_s=400_od_jet_speed_mm_s=1780``.

    Each parameter is named by the shortest tail of its dotted key that is unique among the
    parameters; names that still collide (values equal after formatting) get a ``-N`` suffix.
    """
    short: dict[str, str] = {}
    for key in parameters:
        parts = key.split(".")
        for n in range(1, len(parts) + 1):
            tail = ".".join(parts[-n:])
            if sum(1 for other in parameters if other == tail or other.endswith("." + tail)) == 1:
                short[key] = tail
                break
    names: list[str] = []
    for point in points:
        name = "_".join(f"{short[k]}={_format_value(point[k])}" for k in parameters)
        name = re.sub(r"[^A-Za-z0-9._=+-]", "-", name)
        base, n = name, 1
        while name in names:
            n += 1
            name = f"{base}-{n}"
        names.append(name)
    return names


def flatten_summary(summary: dict[str, Any]) -> dict[str, Any]:
    """The key outputs of a summary.json as ``{dotted name: number}`` (phase fractions: mean only)."""
    out: dict[str, Any] = {}
    for top in KEY_OUTPUTS:
        table = summary.get(top)
        if not isinstance(table, dict):
            continue
        for key, value in flatten(table, top + "."):
            if top == "phases_final" and not key.endswith(".mean"):
                continue
            if top == "solver" and key.split(".")[-1] not in SOLVER_KEYS:
                continue
            if top == "shape_mm" and key.split(".")[1] not in ("after", "change"):
                continue
            if value is None or isinstance(value, bool) or isinstance(value, (int, float)):
                out[key] = value
    tempered = summary.get("tempered")
    if isinstance(tempered, dict):   # a run with a [temper]: the same outputs of the tempered part, and its change
        out.update({f"tempered.{k}": v for k, v in flatten_summary(tempered).items()})
        out.update({f"tempered.change_by_temper_mm.{k}": v
                    for k, v in tempered.get("change_by_temper_mm", {}).items()})
    return out


def case_hash(raw_case: dict[str, Any], condition: str | None, overrides: dict[str, Any]) -> str:
    """A fingerprint of every input of one case (base table, condition, overrides) and of the code and data that
    run it (:func:`quenchsim.fingerprint.run_fingerprint`: changed run code, or an edited material file, is rerun,
    not read from an earlier run's folder; an edit of the code around the runs is not)."""
    text = json.dumps([raw_case, condition, overrides, run_fingerprint()], sort_keys=True, default=str)
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def _write_json(path: Path, data: Any) -> None:
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text(json.dumps(data, indent=2, default=str))
    tmp.replace(path)


# glibc mallopt parameters (malloc.h): M_TRIM_THRESHOLD = -1, M_MMAP_THRESHOLD = -3
_M_TRIM_THRESHOLD, _M_MMAP_THRESHOLD = -1, -3
_KEEP_FREED_BYTES = 64 * 2**20
_MMAP_THRESHOLD_BYTES = 32 * 2**20


def keep_freed_memory() -> bool:
    """Let this process's glibc malloc keep and reuse freed memory; False where there is no glibc.

    A Dask nanny starts its worker with ``MALLOC_TRIM_THRESHOLD_=65536`` (dask's default
    ``distributed.nanny.pre-spawn-environ``). That fixed setting also switches off glibc's dynamic mmap
    threshold, so every numpy array above 128 KiB is mapped and unmapped afresh: a ring-A case then
    takes ~30 % more CPU (32x the page faults) and two such workers slow each other down further in
    the kernel. Raising both thresholds (glibc's dynamic maximum, 32 MiB, for mmap) restores the
    behaviour of a plain ``quenchsim run``; a case's working set is a few hundred MB at most.
    """
    name = ctypes.util.find_library("c")
    try:
        mallopt = ctypes.CDLL(name).mallopt if name else None
    except (OSError, AttributeError):
        mallopt = None
    if mallopt is None:
        return False
    return bool(mallopt(_M_MMAP_THRESHOLD, _MMAP_THRESHOLD_BYTES)) and bool(mallopt(_M_TRIM_THRESHOLD, _KEEP_FREED_BYTES))


def run_point(raw_case: dict[str, Any], case_path: str | None, condition: str | None, overrides: dict[str, Any],
              out_dir: str) -> dict[str, Any]:
    """Run one case of a sweep into ``out_dir`` (executed on a Dask worker; never raises).

    Returns ``{"status": "ok" | "hot" | "failed" | ..., "error": str | None, "summary": dict | None, "wall_s": float,
    "cpu_s": float}`` (wall and CPU time of this process for the case).
    """
    from quenchsim.pipeline import run as run_case

    keep_freed_memory()
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    t0, cpu0 = time.perf_counter(), time.process_time()
    record = {"case": case_path, "condition": condition, "overrides": overrides,
              "inputs_hash": case_hash(raw_case, condition, overrides)}
    _write_json(out / CASE_JSON, record)
    summary_path = out / files.SUMMARY_JSON
    summary_path.unlink(missing_ok=True)
    summary: dict[str, Any] | None
    try:
        case = case_from_dict(raw_case, condition, overrides, path=Path(case_path) if case_path else None)
        RunWriter(out).case(case.resolved())
        summary = run_case(case, out, progress=False).summary
        status, error = str(summary.get("status", "ok")), summary.get("error")
    except Exception as exc:  # noqa: BLE001 -- a sweep records any failure of a case and goes on
        summary = read_summary(out)
        status, error = "failed", f"{type(exc).__name__}: {exc}"
        log.debug("case %s failed:\n%s", out, traceback.format_exc())
    if status not in files.FINISHED_STATUSES:
        _write_json(out / CASE_JSON, {**record, "error": error})
    return {"status": status, "error": error, "summary": summary, "wall_s": time.perf_counter() - t0,
            "cpu_s": time.process_time() - cpu0}


def finished(case_dir: Path, inputs_hash: str) -> dict[str, Any] | None:
    """The summary of a case folder that finished (status ok or hot) for the same inputs, else None."""
    try:
        record = json.loads((case_dir / CASE_JSON).read_text())
    except (OSError, ValueError):
        return None
    summary = read_summary(case_dir)
    return (summary if summary and record.get("inputs_hash") == inputs_hash
            and summary.get("status") in files.FINISHED_STATUSES else None)


class ResultsTable:
    """``results.csv``: one row per finished case in sweep order, rewritten atomically on every update."""

    def __init__(self, path: Path, names: list[str], parameters: list[str]) -> None:
        self.path = path
        self.names = names
        self.parameters = parameters
        self.rows: dict[str, dict[str, Any]] = {}

    def add(self, name: str, point: dict[str, Any], status: str, error: str | None,
            summary: dict[str, Any] | None, timing: dict[str, float] | None = None) -> dict[str, Any]:
        row = {"case": name, "status": status, "error": error or "", **point,
               **(flatten_summary(summary) if summary else {}), **(timing or {})}
        self.rows[name] = row
        self.write()
        return row

    def ordered(self) -> list[dict[str, Any]]:
        return [self.rows[n] for n in self.names if n in self.rows]

    def write(self) -> None:
        rows = self.ordered()
        columns = ["case", "status", "error", *self.parameters]
        for row in rows:
            columns += [k for k in row if k not in columns]
        tmp = self.path.with_name(self.path.name + ".tmp")
        with tmp.open("w", newline="") as fh:
            writer = csv.DictWriter(fh, fieldnames=columns, restval="")
            writer.writeheader()
            for row in rows:
                writer.writerow({k: ("" if v is None else v) for k, v in row.items()})
        tmp.replace(self.path)


def read_results(path: str | Path) -> list[dict[str, Any]]:
    """Read a results.csv back; numeric cells become floats, empty cells None."""
    def cell(value: str) -> Any:
        if value == "":
            return None
        try:
            return float(value)
        except ValueError:
            return value

    with Path(path).open(newline="") as fh:
        return [{k: (v if k in ("case", "status", "error") else cell(v)) for k, v in row.items()}
                for row in csv.DictReader(fh)]


SCHEDULER_TIMEOUT_S = 5.0
"""How long to wait for a Dask scheduler given by address before giving up with one line."""


def _client(scheduler: str | None, workers: int) -> tuple[Any, Any]:
    import dask
    from dask.distributed import Client, LocalCluster

    logging.getLogger("distributed").setLevel(logging.ERROR)
    if scheduler:
        try:
            return Client(scheduler, timeout=f"{SCHEDULER_TIMEOUT_S:g}s"), None
        except (OSError, TimeoutError, ValueError) as exc:
            raise InputError("--scheduler", scheduler,
                             f"no Dask scheduler answered within {SCHEDULER_TIMEOUT_S:g} s ({type(exc).__name__}); start "
                             "one with `dask scheduler` or leave --scheduler out for a local cluster") from None
    # the workers' statistical profiler samples the case's thread every 10 ms: ~6 % of a case's CPU time;
    # worker-saturation 1.0: a case goes to a worker only when its thread is free (the default 1.1 lets a
    # one-thread worker queue a second case, so the last cases can wait behind a long one while the other
    # worker idles)
    with dask.config.set({"distributed.worker.profile.enabled": False,
                          "distributed.scheduler.worker-saturation": 1.0}):
        cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=":0",
                               silence_logs=logging.ERROR)
    return Client(cluster), cluster


def run_sweep(spec: SweepSpec, out_dir: str | Path, scheduler: str | None = None, workers: int = 2,
              progress: bool = True, on_result: Callable[[dict[str, Any]], None] | None = None) -> SweepOutcome:
    """Run every case of ``spec`` not yet finished into ``out_dir`` and keep ``results.csv`` current.

    ``scheduler``: address of a running Dask scheduler (e.g. ``tcp://10.0.0.5:8786``); otherwise a
    LocalCluster with ``workers`` processes of one thread, or (``workers=0``) this process, serially.
    Ctrl-C stops the sweep; everything finished is already on disk and ``interrupted`` is set.
    """
    require(isinstance(workers, int) and workers >= 0, "--workers", workers, "must be an integer >= 0")
    out = Path(out_dir).resolve()
    out.mkdir(parents=True, exist_ok=True)
    names = case_names(spec.parameters, spec.points)
    case_path = str(spec.case_path) if spec.case_path else None
    _write_json(out / SWEEP_JSON, {"name": spec.name, "case": case_path, "condition": spec.condition,
                                   "fixed": spec.fixed, "parameters": spec.parameters,
                                   "cases": [{"name": n, **p} for n, p in zip(names, spec.points)]})
    table = ResultsTable(out / RESULTS_CSV, names, spec.parameters)
    todo: list[tuple[str, dict[str, Any]]] = []
    for name, point in zip(names, spec.points):
        summary = finished(out / name, case_hash(spec.raw_case, spec.condition, spec.overrides(point)))
        if summary is not None:
            table.rows[name] = {"case": name, "status": files.run_status(summary), "error": "", **point,
                                **flatten_summary(summary)}
        else:
            todo.append((name, point))
    table.write()
    skipped = len(spec.points) - len(todo)
    t0 = time.perf_counter()
    ran = failed = 0
    interrupted = False
    bar = tqdm(total=len(spec.points), initial=skipped, desc=f"sweep {spec.name}", unit="case", disable=not progress)
    by_name = dict(todo)

    def record(name: str, result: dict[str, Any]) -> None:
        nonlocal ran, failed
        ran += 1
        failed += result["status"] not in files.FINISHED_STATUSES
        timing = {f"sweep.case_{k}": result[k] for k in ("wall_s", "cpu_s") if k in result}
        row = table.add(name, by_name[name], result["status"], result["error"], result["summary"], timing)
        bar.update(1)
        bar.set_postfix_str(f"{failed} failed" if failed else "")
        if on_result is not None:
            on_result(row)

    args = {name: (spec.raw_case, case_path, spec.condition, spec.overrides(point), str(out / name))
            for name, point in todo}
    try:
        if todo and workers == 0 and not scheduler:
            for name, _ in todo:
                record(name, run_point(*args[name]))
        elif todo:
            interrupted = run_on_dask(args, scheduler, workers, record)
    except KeyboardInterrupt:
        interrupted = True
    finally:
        bar.close()
    rows = table.ordered()
    return SweepOutcome(out_dir=out, rows=rows, skipped=skipped, ran=ran, failed=failed,
                        pending=len(spec.points) - len(rows), wall_time_s=time.perf_counter() - t0,
                        interrupted=interrupted)


def run_on_dask(args: dict[str, tuple[Any, ...]], scheduler: str | None, workers: int,
                record: Callable[[str, dict[str, Any]], None]) -> bool:
    """Submit every case (``name -> run_point arguments``) and record the results as they arrive; True when
    interrupted by Ctrl-C. Also the calibration's and the design study's runner."""
    from dask.distributed import as_completed

    client, cluster = _client(scheduler, workers)
    futures = {}
    try:
        # a base case table shared by several cases (a sweep's) is shipped to the workers once; scattered inside a
        # list: Dask scatters a dict value by value under the dict's own keys ("quench", "geometry", ...), so two
        # tables on one scheduler would share those keys and every case would run the first table's values
        shipped: dict[str, Any] = {}
        for name, (raw_case, *rest) in args.items():
            text = json.dumps(raw_case, sort_keys=True, default=str)
            if text not in shipped:
                shipped[text] = client.scatter([raw_case], broadcast=True)[0]
            futures[client.submit(run_point, shipped[text], *rest, key=f"quenchsim-{name}-{time.time_ns()}",
                                  pure=False)] = name
        for future in as_completed(futures):
            try:
                result = future.result()
            except Exception as exc:  # noqa: BLE001 -- a lost worker fails its case, the rest go on
                result = {"status": "failed", "error": f"{type(exc).__name__}: {exc}", "summary": None}
            record(futures[future], result)
        return False
    except KeyboardInterrupt:
        client.cancel(list(futures))
        return True
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
