"""The runner over ``validation/``: one folder per study, targets as data, pages from metrics + targets.

A study is a folder ``validation/<area>/<study>/`` (contract in validation/README.md) with

* ``targets.toml``: ``[[targets]]`` tables, each naming a ``metric`` the study returns, the published or
  measured value (``value`` + ``tolerance`` | ``value`` + ``rel_tolerance`` | ``min`` / ``max``), its
  ``unit`` and ``source``; ``status = "open"`` (+ ``reason``) for a target known to be missed,
  ``status = "reference"`` for a published value printed beside the computed one without a tolerance
  (never a pass or a miss); ``role = "calibration"`` for a declared calibration point (the model was set
  with it: meeting it is no evidence);
* ``study.py`` with ``TITLE``, ``SLOW`` and ``run(workdir) -> dict`` (named, JSON-serialisable metrics;
  plots as PNG files in ``workdir``), optionally ``page(metrics) -> str`` (the Markdown body).

:func:`run_study` runs a study unless its metrics are cached with the same fingerprint (the code and data the
study depends on: the quenchsim modules it imports, its folder, the case files it names, package and material
data: :func:`study_inputs`), writes ``<reports>/<area>_<study>.md`` (body + target table),
``<area>_<study>.json`` (the metrics, their fingerprint and the files it covers, which
``quenchsim validate --check`` re-evaluates) and copies the study's PNGs.
The ring studies reuse finished quench runs through :func:`cached_run` (resumable, as the pages were).
"""

from __future__ import annotations

import datetime
import functools
import hashlib
import importlib.util
import json
import math
import re
import shutil
import time
import traceback
from dataclasses import dataclass, field, replace
from pathlib import Path
from types import ModuleType
from collections.abc import Callable
from typing import Any

from quenchsim.errors import InputError
from quenchsim.inputs.declare import from_table
from quenchsim.inputs.reader import parse_toml, read_toml, reading
from quenchsim.inputs.targets import Target, TargetsFile
from quenchsim.fingerprint import code_fingerprint

ROOT = Path(__file__).resolve().parents[1]
VALIDATION_ROOT = ROOT / "validation"
RUNS = Path("runs") / "validation"
"""Work folders of the studies (and the cached quench runs), relative to the working directory."""

def load_targets(path: Path, study: str = "") -> list[Target]:
    """The targets of a targets.toml (:class:`quenchsim.inputs.targets.Target`: every target names a metric and a
    non-empty source and has exactly one form), read against their declaration; an error names the file."""
    path = Path(path)
    data = read_toml(path, "targets")
    with reading(path):
        targets = from_table(TargetsFile, data).targets
    return [replace(t, source=t.source.strip(), study=study) for t in targets]


def study_targets(study_file: str | Path) -> dict[str, Target]:
    """The targets of the study whose ``study.py`` is ``study_file``, by metric name (for a page that
    prints a published value in its prose)."""
    folder = Path(study_file).resolve().parent
    return {t.metric: t for t in load_targets(folder / "targets.toml", f"{folder.parent.name}/{folder.name}")}


def metric_value(metrics: dict[str, Any], name: str) -> Any:
    """``metrics`` looked up by a dotted name (``relative.condition_2.time_ratio``; an integer part indexes
    a list); ``None`` when absent."""
    node: Any = metrics
    for part in name.split("."):
        if isinstance(node, dict) and part in node:
            node = node[part]
        elif isinstance(node, list) and part.lstrip("-").isdigit() and -len(node) <= int(part) < len(node):
            node = node[int(part)]
        else:
            return None
    return node


@dataclass(frozen=True)
class Verdict:
    """A target against the computed value: ``met``, ``missed``, ``open`` (a known miss; ``open, met`` once it
    passes: then close it), ``reference``, ``absent`` (the study returned no such metric: a miss) or
    ``skipped`` (the study skipped itself, e.g. a peer code that is not installed: not evaluated, no miss)."""

    target: Target
    value: float | None
    state: str

    @property
    def counts_as_miss(self) -> bool:
        return self.state in ("missed", "absent", "open")


SKIPPED = "skipped"
"""A study that cannot run here (a peer code is not installed) returns ``{"skipped": "skipped: why"}``."""


def evaluate(targets: list[Target], metrics: dict[str, Any]) -> list[Verdict]:
    if isinstance(metrics.get(SKIPPED), str):
        return [Verdict(t, None, SKIPPED) for t in targets]
    out = []
    for t in targets:
        v = metric_value(metrics, t.metric)
        if isinstance(v, bool) or not isinstance(v, (int, float)) or (isinstance(v, float) and math.isnan(v)):
            out.append(Verdict(t, None, "absent" if t.status != "reference" else "reference"))
            continue
        band = t.band()
        ok = band is not None and band[0] <= v <= band[1]
        if t.status == "reference":
            state = "reference"
        elif t.status == "open":
            state = "open, met" if ok else "open"
        else:
            state = "met" if ok else "missed"
        out.append(Verdict(t, float(v), state))
    return out


def _fmt_value(v: float | None) -> str:
    if v is None:
        return "-"
    return f"{v:.4g}" if abs(v) < 1e5 else f"{v:.4e}"


def _cell(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def target_table(verdicts: list[Verdict]) -> list[str]:
    """Markdown table of the verdicts, with each target's source (and the reason of an open one)."""
    if not verdicts:
        return ["No targets (a page of measured facts: benchmarks, sensitivities)."]
    lines = ["| metric | computed | target | status | role | source |", "|---|---|---|---|---|---|"]
    for v in verdicts:
        t = v.target
        state = {"met": "met", "missed": "**MISSED**", "absent": "**MISSED** (no value)", "open": "open (known miss)",
                 "open, met": "open, now met", "reference": "reference", SKIPPED: "skipped (not evaluated)"}[v.state]
        what = _cell(t.metric + (f": {t.description}" if t.description else ""))
        note = f" -- open: {t.reason}" if t.status == "open" else ""
        lines.append(f"| {what} | {_fmt_value(v.value)} | {t.describe()} | {state} | {t.role} | "
                     f"{_cell(t.source + note)} |")
    return lines


# ------------------------------------------------------------------------------------------------ studies

@dataclass
class Study:
    """A folder of validation/: ``area/name``, its targets and (loaded on demand) its module."""

    area: str
    name: str
    folder: Path
    targets: list[Target]
    _module: ModuleType | None = field(default=None, repr=False)

    @property
    def key(self) -> str:
        return f"{self.area}/{self.name}"

    @property
    def slug(self) -> str:
        return f"{self.area}_{self.name}"

    @property
    def module(self) -> ModuleType:
        if self._module is None:
            module = study_module(self.key, self.folder.parents[1])
            for attr in ("TITLE", "SLOW", "run"):
                if not hasattr(module, attr):
                    raise InputError(str(self.folder / "study.py"), attr, "a study defines TITLE, SLOW and run(workdir)")
            self._module = module
        return self._module

    def _constant(self, name: str, default: Any) -> Any:
        """A module-level constant read from study.py's source without importing it (for --list)."""
        import ast

        node: Any   # a statement; an assignment's .value is read
        for node in ast.parse((self.folder / "study.py").read_text()).body:
            target = node.targets[0] if isinstance(node, ast.Assign) else getattr(node, "target", None)
            if isinstance(target, ast.Name) and target.id == name and isinstance(node.value, ast.Constant):
                return node.value.value
        return default

    def title(self) -> str:
        return str(self._constant("TITLE", self.key))

    def slow(self) -> bool:
        return bool(self._constant("SLOW", True))


@functools.lru_cache(maxsize=None)
def study_module(key: str, root: Path = VALIDATION_ROOT) -> ModuleType:
    """The study.py of ``area/study`` under ``root``, loaded once (a study uses another's helpers or runs)."""
    path = Path(root) / key / "study.py"
    spec = importlib.util.spec_from_file_location(f"quenchsim_validation_{key.replace('/', '_')}", path)
    if spec is None or spec.loader is None or not path.is_file():
        raise InputError("study", key, f"no {path}")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def discover(root: Path = VALIDATION_ROOT) -> list[Study]:
    """Every ``<area>/<study>/`` of ``root`` holding a study.py, sorted by area and name."""
    studies = []
    for study_py in sorted(Path(root).glob("*/*/study.py")):
        folder = study_py.parent
        key = f"{folder.parent.name}/{folder.name}"
        targets_file = folder / "targets.toml"
        if not targets_file.is_file():
            raise InputError(str(targets_file), "missing", "every study folder holds a targets.toml")
        studies.append(Study(folder.parent.name, folder.name, folder, load_targets(targets_file, key)))
    return studies


def select(studies: list[Study], only: list[str] | None) -> list[Study]:
    """The studies named by ``only`` (``area/study``, an area, or a study name); all when ``only`` is empty."""
    if not only:
        return studies
    chosen, unknown = [], []
    for name in only:
        hit = [s for s in studies if name in (s.key, s.area, s.name)]
        if not hit:
            unknown.append(name)
        chosen += [s for s in hit if s not in chosen]
    if unknown:
        raise InputError("--only", unknown, "known studies: " + ", ".join(s.key for s in studies))
    return chosen


# ------------------------------------------------------------------------------------------- fingerprints

STUDY_MODULE_CALL = re.compile(r"study_module\(\s*[\"']([\w./-]+)[\"']")
"""A study that uses another's helpers or runs names it: ``study_module("quench/ring_a")``."""


@dataclass(frozen=True)
class StudyInputs:
    """What a study's results depend on, as paths relative to the checkout: ``code`` (the quenchsim modules of
    its import closure, :func:`quenchsim.dependencies.code_closure`, and ``path::name`` for the runner helpers it
    takes), ``data`` (its folder and those of the studies it uses, the package data of its modules, the case
    files its files name and, when its modules read it, the materials folder) and their ``fingerprint``."""

    code: tuple[str, ...]
    data: tuple[str, ...]
    fingerprint: str

    def record(self) -> dict[str, list[str]]:
        return {"code": list(self.code), "data": list(self.data)}


def _study_folders(study: Study) -> list[Path]:
    """The study's folder and those of the studies it uses through ``study_module`` (recursively)."""
    root = study.folder.parents[1]
    folders, todo = [], [study.folder]
    while todo:
        folder = todo.pop()
        if folder in folders:
            continue
        folders.append(folder)
        for py in folder.glob("*.py"):
            todo += [root / key for key in STUDY_MODULE_CALL.findall(py.read_text()) if (root / key).is_dir()]
    return folders


def study_inputs(study: Study, root: Path = ROOT) -> StudyInputs:
    """The code and data ``study`` depends on (``root``: the checkout holding quenchsim/, cases/, materials/)."""
    from quenchsim.behaviour import behaviour_bytes
    from quenchsim.dependencies import code_closure, data_files, named_files, package_data
    from quenchsim.materials import materials_dir

    root = Path(root)
    checkout = study.folder.parents[2]
    folders = _study_folders(study)
    own = [p for f in folders for p in sorted(f.rglob("*"))
           if p.is_file() and "__pycache__" not in p.parts and p.suffix != ".pyc"]
    texts = {p: p.read_text(errors="replace") for p in own if p.suffix in (".py", ".toml")}
    closure = code_closure([t for p, t in texts.items() if p.suffix == ".py"], root)
    materials = materials_dir() if root == ROOT else root / "materials"
    data = [*own, *package_data(closure), *named_files(texts.values(), root / "cases")]
    if closure.reads_materials:
        data += data_files(materials)

    def name(path: Path) -> str:
        for base, prefix in ((checkout, ""), (root, ""), (materials, "materials/")):
            if path.is_relative_to(base):
                return prefix + path.relative_to(base).as_posix()
        return path.as_posix()

    digest = hashlib.sha1(b"study inputs v3")
    code = sorted({name(p): p for p in closure.modules.values()}.items())
    files = sorted({name(p): p for p in data}.items())
    for key, path in [*code, *files]:
        digest.update(f"\0{key}\0".encode())
        digest.update(behaviour_bytes(path))
    for key, source in sorted(closure.parts.items()):
        digest.update(f"\0{key}\0{source}".encode())
    return StudyInputs(tuple([k for k, _ in code] + sorted(closure.parts)), tuple(k for k, _ in files),
                       digest.hexdigest())


def study_fingerprint(study: Study, root: Path = ROOT) -> str:
    """The fingerprint of :func:`study_inputs`."""
    return study_inputs(study, root).fingerprint


def is_current(record: dict[str, Any] | None, inputs: StudyInputs) -> bool:
    """True when ``record`` was computed from ``inputs``: same fingerprint, and written by this scheme (a record
    without its ``inputs`` list predates it and counts as stale, never as fresh)."""
    return (record is not None and isinstance(record.get("inputs"), dict)
            and record.get("fingerprint") == inputs.fingerprint)


def _toml(case: Any) -> str:
    import tomli_w

    return tomli_w.dumps(case.resolved())


def page_written_by(write: Callable[[Path], list], metrics: dict[str, Any], workdir: Path) -> dict[str, Any]:
    """Run a study whose page code writes its own Markdown page (and PNGs) into ``workdir`` while recording its
    named metrics in ``metrics``: the metrics plus the page's body as ``page_md`` (the runner writes the title)."""
    metrics.clear()
    paths = [Path(p) for p in write(Path(workdir))]
    page_file = next(p for p in paths if p.suffix == ".md")
    lines = page_file.read_text().splitlines()
    page_file.unlink()
    body = lines[1:]
    while body and not body[0].strip():
        body = body[1:]
    return {**metrics, "page_md": "\n".join(body) + "\n"}


def written_page(metrics: dict[str, Any]) -> str:
    """The ``page`` of a study run through :func:`page_written_by`."""
    return metrics["page_md"]


def cached_run(case: Any, run_dir: Path) -> Path:
    """Run ``case`` into ``run_dir`` unless the same resolved inputs already finished there with the same
    code and data (:func:`code_fingerprint`), so an interrupted ``quenchsim validate`` resumes cheaply and
    a changed model is always rerun."""
    from quenchsim.pipeline import run as run_case
    from quenchsim.results import files

    done, stamp = run_dir / files.SUMMARY_JSON, run_dir / "code_fingerprint.txt"
    fingerprint = code_fingerprint()
    if done.is_file() and (run_dir / files.CASE_TOML).is_file() and stamp.is_file():
        same = read_toml(run_dir / files.CASE_TOML) == parse_toml(_toml(case), "case")
        if same and stamp.read_text() == fingerprint and json.loads(done.read_text()).get("status") == "ok":
            return run_dir
    stamp.unlink(missing_ok=True)
    run_case(case, run_dir, progress=True)
    stamp.write_text(fingerprint)
    return run_dir


def refined_case(case_path: Path, condition: str | None, mesh: float = 1.0, step: float = 1.0) -> Any:
    """The case with element sizes times ``mesh`` and step limits times ``step`` (convergence studies)."""
    from quenchsim.case import load_case

    return load_case(case_path, condition).refined(mesh=mesh, step=step)


# ------------------------------------------------------------------------------------------------- runner

@dataclass
class StudyResult:
    """What one study did: ``ran`` / ``cached`` / ``failed`` / ``not run`` (``--check`` without metrics)."""

    key: str
    status: str
    seconds: float = 0.0
    error: str = ""
    files: list[str] = field(default_factory=list)
    verdicts: list[Verdict] = field(default_factory=list)
    stale: bool = False

    def misses(self) -> list[Verdict]:
        return [v for v in self.verdicts if v.counts_as_miss]


def _json_default(x: Any) -> Any:
    import numpy as np

    if isinstance(x, np.generic):
        return x.item()
    if isinstance(x, np.ndarray):
        return x.tolist()
    if isinstance(x, Path):
        return str(x)
    raise TypeError(f"not JSON-serialisable: {type(x).__name__}")


def cached_metrics(study: Study, reports_dir: Path) -> dict[str, Any] | None:
    """The record ``<reports>/<area>_<study>.json`` of the last run (metrics, fingerprint, seconds), if any."""
    path = Path(reports_dir) / f"{study.slug}.json"
    try:
        record = json.loads(path.read_text())
    except (OSError, ValueError):
        return None
    return record if isinstance(record, dict) and "metrics" in record else None


def page_markdown(study: Study, metrics: dict[str, Any], verdicts: list[Verdict], fingerprint: str) -> str:
    """The page: title, the study's body (``page(metrics)``, else its scalar metrics) and the target table."""
    module = study.module
    if hasattr(module, "page"):
        body = module.page(metrics)
    else:
        rows = [(k, v) for k, v in metrics.items() if isinstance(v, (int, float)) and not isinstance(v, bool)]
        body = "\n".join(["| metric | value |", "|---|---|", *(f"| {k} | {_fmt_value(float(v))} |" for k, v in rows)])
    lines = [f"# {module.TITLE}", "",
             f"Generated by `quenchsim validate` from `validation/{study.key}/` (study.py, targets.toml); "
             f"fingerprint {fingerprint[:12]}.", "", body.rstrip(), "", "## Targets", "",
             *target_table(verdicts), ""]
    return "\n".join(lines)


def run_study(study: Study, reports_dir: Path, runs_dir: Path = RUNS, force: bool = False) -> StudyResult:
    """Run ``study`` (or reuse its cached metrics), write its page, metrics record and PNGs; never raises. The study
    sees the shipped data only (:func:`quenchsim.materials.shipped_data_only`): a user's ``./materials`` or
    ``QUENCHSIM_DATA`` folder never changes which steel or oil it loads, nor its fingerprint."""
    from quenchsim.materials import shipped_data_only

    with shipped_data_only():
        return _run_study(study, reports_dir, runs_dir, force)


def _run_study(study: Study, reports_dir: Path, runs_dir: Path, force: bool) -> StudyResult:
    reports_dir, runs_dir = Path(reports_dir), Path(runs_dir)
    reports_dir.mkdir(parents=True, exist_ok=True)
    try:
        inputs = study_inputs(study)
        fingerprint = inputs.fingerprint
        record = cached_metrics(study, reports_dir)
        t0 = time.perf_counter()
        if (not force and record is not None and is_current(record, inputs)
                and not isinstance(record["metrics"].get(SKIPPED), str)):  # a skipped study is retried
            status, metrics, seconds = "cached", record["metrics"], float(record.get("seconds", 0.0))
            files = list(record.get("files", []))
        else:
            workdir = runs_dir / study.area / study.name
            workdir.mkdir(parents=True, exist_ok=True)
            for old in workdir.glob("*.png"):
                old.unlink()
            metrics = study.module.run(workdir)
            seconds = time.perf_counter() - t0
            status = "ran"
            files = []
            for png in sorted(workdir.glob("*.png")):
                shutil.copy2(png, reports_dir / png.name)
                files.append(png.name)
            record = {"study": study.key, "fingerprint": fingerprint, "inputs": inputs.record(),
                      "seconds": seconds, "files": files,
                      "generated_utc": f"{datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M}",
                      "metrics": metrics}
            text = json.dumps(record, indent=1, default=_json_default, allow_nan=True)
            (reports_dir / f"{study.slug}.json").write_text(text)
            metrics = json.loads(text)["metrics"]
        verdicts = evaluate(study.targets, metrics)
        if isinstance(metrics.get(SKIPPED), str):
            status = SKIPPED
        (reports_dir / f"{study.slug}.md").write_text(page_markdown(study, metrics, verdicts, fingerprint))
        return StudyResult(study.key, status, seconds, files=[f"{study.slug}.md", f"{study.slug}.json", *files],
                           verdicts=verdicts)
    except Exception as exc:  # noqa: BLE001 -- a broken study is reported and the others still run
        return StudyResult(study.key, "failed", error=f"{type(exc).__name__}: {exc}\n{traceback.format_exc(limit=-3)}")


def check_study(study: Study, reports_dir: Path) -> StudyResult:
    """The study's targets against its cached metrics (no run); ``not run`` when there are none."""
    record = cached_metrics(study, reports_dir)
    if record is None:
        return StudyResult(study.key, "not run", error=f"no {study.slug}.json in {reports_dir}")
    stale = not is_current(record, study_inputs(study))
    return StudyResult(study.key, "cached", float(record.get("seconds", 0.0)),
                       verdicts=evaluate(study.targets, record["metrics"]), stale=stale)


def write_index(reports_dir: Path, studies: list[Study], results: dict[str, StudyResult]) -> Path:
    """reports/README.md (one row per study: page, targets met / missed / open, time) and index.json."""
    reports_dir = Path(reports_dir)
    lines = ["# quenchsim reports", "",
             f"Generated by `quenchsim validate` ({datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC) "
             "from the studies in validation/ (see validation/README.md); do not edit by hand.", "",
             "| study | page | status | met | missed | open | reference | time (s) |", "|---|---|---|---|---|---|---|---|"]
    index = []
    for s in studies:
        r = results.get(s.key)
        if r is None:
            continue
        count = {k: sum(v.state.startswith(k) for v in r.verdicts) for k in ("met", "open", "reference")}
        missed = sum(v.state in ("missed", "absent") for v in r.verdicts)
        page = f"[{s.title()}]({s.slug}.md)" if (reports_dir / f"{s.slug}.md").is_file() else "-"
        status = r.status if r.status != "failed" else f"failed: {r.error.splitlines()[0]}".replace("|", "/")
        lines.append(f"| `{s.key}` | {page} | {status} | {count['met']} | {missed} | {count['open']} | "
                     f"{count['reference']} | {r.seconds:.1f} |")
        index.append({"study": s.key, "status": r.status, "seconds": r.seconds, "files": r.files, "error": r.error,
                      "verdicts": [{"metric": v.target.metric, "value": v.value, "state": v.state} for v in r.verdicts]})
    (reports_dir / "index.json").write_text(json.dumps(index, indent=1))
    readme = reports_dir / "README.md"
    readme.write_text("\n".join(lines) + "\n")
    return readme


def previous_results(reports_dir: Path, studies: list[Study]) -> dict[str, StudyResult]:
    """Rows of the studies not run this time, from their cached metrics (so the index stays complete)."""
    out = {}
    for s in studies:
        r = check_study(s, reports_dir)
        if r.status != "not run":
            out[s.key] = r
    return out


def summary_lines(results: list[StudyResult]) -> list[str]:
    """The printed table: every target that is not met, grouped as missed / open; then a count."""
    lines = []
    missed = [(r, v) for r in results for v in r.verdicts if v.state in ("missed", "absent")]
    open_ = [(r, v) for r in results for v in r.verdicts if v.state.startswith("open")]
    met = sum(v.state == "met" for r in results for v in r.verdicts)
    for label, rows in (("MISSED", missed), ("OPEN (known misses)", open_)):
        if rows:
            lines.append(f"{label}:")
            for r, v in rows:
                extra = f"  [{v.target.reason}]" if v.target.status == "open" else ""
                lines.append(f"  {r.key}: {v.target.metric} = {_fmt_value(v.value)} (target {v.target.describe()})"
                             f"{' -- now met: close it' if v.state == 'open, met' else ''}{extra}")
    failed = [r for r in results if r.status in ("failed", "not run")]
    for r in failed:
        lines.append(f"{r.key}: {r.status}: {r.error.splitlines()[0] if r.error else ''}")
    stale = [r.key for r in results if r.stale]
    if stale:
        lines.append(f"stale (code, cases or study changed since these metrics): {', '.join(stale)}")
    lines.append(f"{met} met, {len(missed)} missed, {len(open_)} open, {len(failed)} studies failed/not run")
    return lines


def exit_code(results: list[StudyResult], strict: bool = False) -> int:
    """1 on a regression -- a target not declared open is missed -- or when a study failed / has no metrics;
    an open target that is missed (a declared, known miss) is reported and fails only when ``strict``; else 0."""
    def fails(v: Verdict) -> bool:
        return v.state in ("missed", "absent") or (strict and v.counts_as_miss)

    return int(any(r.status in ("failed", "not run") or any(fails(v) for v in r.verdicts) for r in results))

