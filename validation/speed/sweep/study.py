"""reports/sweep.md: the example nozzle sweep (cases/sweep_nozzles.toml) run one case after another and on
Dask with 2 workers -- wall times, speed-up, identical results -- and its response plots.

``write(reports_dir)`` runs the sweep three times from scratch, each as a real ``quenchsim sweep`` command
started in a new session: serially (``--workers 0``), on a LocalCluster (``--workers 2``), and against a
separately started ``dask scheduler`` with two ``dask worker`` processes, each in its own session. About
6 x 15 s of CPU per run on this machine.

Why three: Linux groups the processes of a login session (``setsid``) into one scheduling group when
``kernel.sched_autogroup_enabled = 1`` and shares the CPU fairly *between groups*. On a machine busy
with other sessions, a LocalCluster (client, nannies and workers all in one session) gets one group's
share however many workers it has; workers started on their own -- as on a cluster, or by a batch
system -- each get a share. On a machine with idle cores both behave the same.
"""

from __future__ import annotations

import json
import os
import pathlib
import socket
import subprocess
import sys
import tempfile
import time
from typing import Any

from quenchsim.report import report_plots
from quenchsim.report.run_report import fmt, response_columns
from quenchsim.sweep import RESULTS_CSV, load_sweep, read_results
from quenchsim.validation import page_written_by, written_page

TITLE = "Parameter sweeps on Dask: the ring-A nozzle sweep"
SLOW = True

SWEEP_FILE = pathlib.Path(__file__).resolve().parents[3] / "cases" / "sweep_nozzles.toml"
WORKERS = 2
AUTOGROUP = pathlib.Path("/proc/sys/kernel/sched_autogroup_enabled")


def _sweep(out: pathlib.Path, *options: str) -> dict[str, Any]:
    """Run ``quenchsim sweep`` in a new session; wall time, load averages and the rows of results.csv."""
    load0 = os.getloadavg()[0]
    t0 = time.perf_counter()
    res = subprocess.run([sys.executable, "-m", "quenchsim.cli", "sweep", str(SWEEP_FILE), "--out", str(out),
                          "--quiet", *options], capture_output=True, text=True, start_new_session=True)
    wall = time.perf_counter() - t0
    if res.returncode not in (0, 1):
        raise RuntimeError(f"quenchsim sweep {' '.join(options)} exited with {res.returncode}: {res.stderr[-2000:]}")
    outcome = json.loads(res.stdout[res.stdout.index("{"):res.stdout.rindex("}") + 1])
    return {"outcome": outcome, "rows": read_results(out / RESULTS_CSV), "wall_s": wall,
            "load": (load0, os.getloadavg()[0])}


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def _with_separate_workers(out: pathlib.Path, scratch: pathlib.Path) -> dict[str, Any]:
    """The sweep against ``dask scheduler`` + WORKERS ``dask worker`` processes, each in its own session."""
    from dask.distributed import Client

    port = _free_port()
    address = f"tcp://127.0.0.1:{port}"
    dask = [sys.executable, "-m", "dask"]
    quiet = {"stdout": subprocess.DEVNULL, "stderr": subprocess.DEVNULL, "start_new_session": True}
    procs = [subprocess.Popen([*dask, "scheduler", "--host", "127.0.0.1", "--port", str(port), "--no-dashboard"],
                              **quiet)]
    try:
        for i in range(WORKERS):
            procs.append(subprocess.Popen([*dask, "worker", address, "--nworkers", "1", "--nthreads", "1",
                                           "--no-dashboard", "--local-directory", str(scratch / f"w{i}")],
                                          env={**os.environ, "DASK_DISTRIBUTED__WORKER__PROFILE__ENABLED": "False"},
                                          **quiet))
        with Client(address, timeout="120s") as client:
            client.wait_for_workers(WORKERS, timeout=300)
        return _sweep(out, "--scheduler", address)
    finally:
        for p in reversed(procs):
            p.terminate()
        for p in procs:
            try:
                p.wait(timeout=60)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait()


def _numeric(row: dict[str, Any]) -> dict[str, float]:
    return {k: v for k, v in row.items() if isinstance(v, float) and not k.startswith(("solver.", "sweep."))}


def _case_times(rows: list[dict[str, Any]]) -> tuple[float, float]:
    """Sum over the cases of (wall time, CPU time of the process that ran it), s."""
    wall = sum(r.get("sweep.case_wall_s") or 0.0 for r in rows)
    cpu = sum(r.get("sweep.case_cpu_s") or 0.0 for r in rows)
    return wall, cpu


def _write(reports_dir: pathlib.Path) -> list[pathlib.Path]:
    reports_dir = pathlib.Path(reports_dir)
    reports_dir.mkdir(parents=True, exist_ok=True)
    spec = load_sweep(SWEEP_FILE)
    with tempfile.TemporaryDirectory(prefix="quenchsim-sweep-bench-") as tmp:
        root = pathlib.Path(tmp)
        runs = {"serial": _sweep(root / "serial", "--workers", "0"),
                "local": _sweep(root / "local", "--workers", str(WORKERS)),
                "separate": _with_separate_workers(root / "separate", root)}
    names = {"serial": "serial (`--workers 0`)", "local": f"LocalCluster (`--workers {WORKERS}`), one session",
             "separate": f"`dask scheduler` + {WORKERS} `dask worker`, a session each (`--scheduler ADDRESS`)"}
    base = runs["serial"]
    n = len(spec.points)
    rows = runs["local"]["rows"]
    ok = [r for r in rows if r["status"] == "ok"]
    diffs = [abs(a[k] - b[k]) for other in ("local", "separate") for a, b in zip(base["rows"], runs[other]["rows"])
             for k in _numeric(a) if isinstance(b.get(k), float)]
    png = reports_dir / "sweep_responses.png"
    outputs = response_columns(ok)
    if ok and outputs:
        png.write_bytes(report_plots.responses(ok, "quench.bath.od_jet_speed_mm_s", ["quench.bath.id_jet_speed_mm_s"],
                                               outputs, "Ring A nozzle sweep: outputs against the OD jet speed"))
    autogroup = AUTOGROUP.read_text().strip() if AUTOGROUP.is_file() else "not available"
    lines = [
        "# Parameter sweeps on Dask: the ring-A nozzle sweep", "",
        f"Sweep file: "
        f"`cases/sweep_nozzles.toml` -- {n} cases, ID jet speeds x OD jet speeds of ring A (condition 1 as the base, "
        "bath model, coarse mesh, the case file's oil and air stages; see the file's header).", "",
        "## Serial against Dask with 2 workers", "",
        "Each run is a `quenchsim sweep` command started in a new session from an empty output directory; the wall "
        "time includes starting Python, the cluster, and stopping it.", "",
        "| run | wall time (s) | speed-up vs serial | cases ok / failed | sum of case wall times (s) | "
        "sum of case CPU times (s) | CPU share of a core per case | cases in flight (case wall sum / wall) | "
        "load average (1 min) before -> after |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for key, r in runs.items():
        o = r["outcome"]
        wall, cpu = _case_times(r["rows"])
        lines.append(f"| {names[key]} | {r['wall_s']:.1f} | {base['wall_s'] / r['wall_s']:.2f}x | "
                     f"{o['ran'] - o['failed']} / {o['failed']} | {wall:.1f} | {cpu:.1f} | {cpu / wall:.2f} | "
                     f"{wall / r['wall_s']:.2f} | {r['load'][0]:.1f} -> {r['load'][1]:.1f} |")
    lines += [
        "", f"Machine: {os.cpu_count()} cores, `kernel.sched_autogroup_enabled` = {autogroup}, shared with other "
        "users' jobs while this ran (load averages above).", "",
        "How to read it: the speed-up is the cases in flight (how well Dask keeps the workers busy; "
        f"{WORKERS} is ideal, less is start-up and the tail of the last case) times the CPU share each case gets "
        "relative to the serial run. With autogroup scheduling a session gets one fair share of a busy machine: "
        "the LocalCluster's workers split that share between them (CPU share per case falls, no speed-up), while "
        "workers in their own sessions get a share each -- the situation of a LocalCluster on a machine with free "
        "cores, and of workers on cluster nodes. Re-run `quenchsim validate --only sweep_bench` on a quiet machine "
        "for an idle-machine timing.", "",
        f"Results are identical between the runs: the largest absolute difference over {len(diffs)} numeric outputs "
        f"is {max(diffs) if diffs else float('nan'):.3g}.", "",
        "## Responses", "",
    ]
    if ok and outputs:
        lines += [f"![responses]({png.name})", ""]
    header = ["case", "status", *spec.parameters, *outputs]
    lines += ["| " + " | ".join(h.replace("quench.bath.", "") for h in header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(fmt(r.get(h)) for h in header) + " |" for r in rows]
    failed = [(key, r) for key, run in runs.items() for r in run["rows"] if r["status"] != "ok"]
    if failed:
        lines += ["", "Failed cases:", ""] + [f"- {names[key]}, {r['case']}: {r['error']}" for key, r in failed]
    lines.append("")
    page = reports_dir / "sweep.md"
    page.write_text("\n".join(lines))
    return [page] + ([png] if png.is_file() else [])


METRICS: dict = {}
"""Named metrics the page code records while it runs (the targets' metrics)."""


def run(workdir: pathlib.Path) -> dict:
    """Run the study: the page code writes its page and PNGs into ``workdir``; the page becomes the body."""
    return page_written_by(_write, METRICS, workdir)


page = written_page
