"""The run/sweep report: every plot present, missing files named, renders in a real browser (Chromium)."""

from __future__ import annotations

import base64
import importlib.util
import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

import matplotlib.image as mpimg
import numpy as np
import pytest
import tomli_w

from quenchsim.report.run_report import write_report
from quenchsim.sweep import make_sweep, run_sweep

ROOT = Path(__file__).resolve().parents[1]
RUN_PLOTS = ["Cooling curves at the probes", "Phase fractions, final state", "Hardness map, final state",
             "Hardness-depth traverse", "Distortion x10 over the pre-quench outline", "Residual hoop-stress traverse",
             "Distortion budget: what the dimension change is made of"]
MEASURED = {"source": "made-up numbers for the test", "before_mm": {"id": 40.0, "od": 50.0, "width": 20.0},
            "after_mm": {"id": 40.03, "od": 50.05}}


def _case() -> dict:
    spec = importlib.util.spec_from_file_location("example_sweep_script", ROOT / "cases" / "example_sweep_script.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    case = module.build_case(wall_mm=5.0, mesh_mm=4.0, quench_time_s=20.0, air_time_s=10.0)
    case["mechanics"] = {"enabled": True}
    case["measured"] = MEASURED
    return case


@pytest.fixture(scope="module")
def dirs(tmp_path_factory) -> dict[str, Path]:
    """A small run with mechanics (through the CLI, so case.toml is written) and a 2-case sweep."""
    root = tmp_path_factory.mktemp("report")
    (root / "ring.toml").write_text(tomli_w.dumps(_case()))
    res = subprocess.run([sys.executable, "-m", "quenchsim.cli", "run", str(root / "ring.toml"), "--out",
                          str(root / "run"), "--quiet"], capture_output=True, text=True, timeout=300)
    assert res.returncode == 0, res.stderr
    case = _case()
    case["mechanics"] = {"enabled": False}
    run_sweep(make_sweep(case, grid={"quench.time_s": [10.0, 20.0]}, name="t"), root / "sweep", workers=0,
              progress=False)
    return {"root": root, "run": root / "run", "sweep": root / "sweep"}


@pytest.fixture(scope="module")
def report(dirs) -> list[Path]:
    """One report of the run and the sweep (HTML, Markdown, PNGs), shared by the tests below."""
    return write_report([dirs["run"], dirs["sweep"]], dirs["root"] / "report" / "report.html")


def _images(html: str) -> dict[str, bytes]:
    return {alt: base64.b64decode(data) for alt, data in
            re.findall(r'<img alt="([^"]+)" src="data:image/png;base64,([A-Za-z0-9+/=]+)">', html)}


def test_run_report_shows_every_plot_and_the_dimension_table(dirs, report):
    written = report
    html = written[0].read_text()
    images = _images(html)
    assert set(RUN_PLOTS) <= set(images)
    assert all(png.startswith(b"\x89PNG") and len(png) > 5000 for png in images.values())
    assert "Not in this run directory" not in html and "Not in this sweep directory" not in html
    # dimension table: the measured change is after - before of the case's [measured] table
    summary = json.loads((dirs["run"] / "summary.json").read_text())
    row = re.search(r"<tr><td>id</td>(.*?)</tr>", html).group(1)
    cells = re.findall(r"<td>([^<]*)</td>", row)
    # lengths in the report: 3 fixed decimals of a mm (issue 47), so to within 0.0005 mm
    assert float(cells[2]) == pytest.approx(summary["dimensions_mm"]["change"]["id"], abs=5e-4)
    assert float(cells[5]) == pytest.approx(0.03, abs=5e-4)
    assert float(cells[6]) == pytest.approx(summary["dimensions_mm"]["change"]["id"] - 0.03, abs=5e-4)
    # distortion budget: its total is the run's dimension change and its parts add up to it
    budget = summary["distortion_budget_mm"]
    for key in ("id", "od", "width"):
        assert budget["total"][key] == pytest.approx(summary["dimensions_mm"]["change"][key], abs=1e-9)
        assert abs(sum(part[key] for part in budget["parts"].values()) - budget["total"][key]) < 2e-3
    row = re.search(r"<tr><td>total \(after - before\)</td>(.*?)</tr>", html).group(1)
    assert float(re.findall(r"<td>([^<]*)</td>", row)[0]) == pytest.approx(budget["total"]["id"], abs=5e-4)
    # shape measures: in summary.json (the bore at mid-width is the caliper's ID) and in the report's table
    shape = summary["shape_mm"]
    assert shape["after"]["bore_at_mid"] == pytest.approx(summary["dimensions_mm"]["after"]["id"], abs=1e-6)
    for key in ("bore_crown", "od_taper", "top_face_dish"):
        row = re.search(rf"<tr><td>{key}</td>(.*?)</tr>", html).group(1)
        assert float(re.findall(r"<td>([^<]*)</td>", row)[2]) == pytest.approx(shape["change"][key], abs=5e-4)
    # the Markdown twin links the same plots, written as files
    md = written[1].read_text()
    links = re.findall(r"!\[([^\]]+)\]\(([^)]+)\)", md)
    assert {alt for alt, _ in links} == set(images)
    assert all((written[1].parent / link).is_file() for _, link in links)


def test_missing_outputs_are_named(dirs, tmp_path):
    run = tmp_path / "partial"
    shutil.copytree(dirs["run"], run)
    for name in ("outline.csv", "residual_hoop_traverse.csv", "hardness_traverse.csv"):
        (run / name).unlink()
    html = write_report([run], tmp_path / "p.html")[0].read_text()
    images = _images(html)
    assert "Distortion x10 over the pre-quench outline" not in images
    assert "Cooling curves at the probes" in images
    for name in ("outline.csv", "residual_hoop_traverse.csv", "hardness_traverse.csv"):
        assert f"no {name}" in html


def test_several_runs_are_compared(dirs, tmp_path):
    other = tmp_path / "other"
    shutil.copytree(dirs["run"], other)
    html = write_report([dirs["run"], other], tmp_path / "c.html")[0].read_text()
    images = _images(html)
    assert {"Cooling curves compared", "Hardness-depth traverses compared"} <= set(images)
    assert html.count("<figcaption>Cooling curves at the probes</figcaption>") == 2


def test_sweep_report_plots_outputs_against_the_swept_input(report):
    html = report[0].read_text()
    assert "Responses against quench.time_s" in _images(html)
    assert "0 of 2 cases ok, 2 finished with the part still hot" in html   # 10 s of air: status hot
    # the response table holds the swept input of each case and an output that differs between them
    rows = re.findall(r"<tr><td>time_s=(\d+)</td><td>hot</td><td>([^<]*)</td>", html)
    assert [(c, float(v)) for c, v in rows] == [("10", 10.0), ("20", 20.0)]


def test_report_cli_rejects_a_directory_without_run_output(tmp_path):
    res = subprocess.run([sys.executable, "-m", "quenchsim.cli", "report", str(tmp_path)],
                         capture_output=True, text=True, timeout=120)
    assert res.returncode == 2
    assert "RUN_DIR" in res.stderr and len(res.stderr.strip().splitlines()) == 1


CHECK_HEAD = ("<script>window.__errs=[];window.addEventListener('error',function(e){"
              "window.__errs.push(String(e.message||(e.target&&e.target.tagName)))},true);</script>")
CHECK_TAIL = ("<script>window.addEventListener('load',function(){var r=[];"
              "document.querySelectorAll('img').forEach(function(i){r.push([i.alt,i.complete,i.naturalWidth])});"
              "var p=document.createElement('pre');p.id='qs-check';"
              "p.textContent=JSON.stringify({errors:window.__errs,images:r});document.body.appendChild(p);});</script>")


def _chromium(args: list[str], tmp_path: Path) -> subprocess.CompletedProcess:
    exe = shutil.which("chromium") or shutil.which("chromium-browser")
    return subprocess.run([exe, "--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
                           "--disable-component-update", "--disable-sync", "--no-first-run",
                           f"--user-data-dir={tmp_path / 'profile'}", "--virtual-time-budget=10000", *args],
                          capture_output=True, text=True, timeout=180)


def _browser_check(html_path: Path, tmp_path: Path) -> dict:
    """Load a copy of the page with an error listener and an image probe; return what the page saw."""
    page = tmp_path / f"check_{html_path.name}"
    page.write_text(html_path.read_text().replace("<head>", "<head>" + CHECK_HEAD, 1)
                    .replace("</body>", CHECK_TAIL + "</body>"))
    res = _chromium(["--dump-dom", page.as_uri()], tmp_path)
    found = re.search(r'<pre id="qs-check">(.*?)</pre>', res.stdout, re.S)
    assert found, f"the page did not finish loading: {res.stderr[-2000:]}"
    return json.loads(found.group(1))


@pytest.mark.skipif(not (shutil.which("chromium") or shutil.which("chromium-browser")),
                    reason="Chromium is not installed (Debian: apt-get install chromium)")
def test_report_renders_in_headless_chromium(report, tmp_path):
    html_path = report[0]
    seen = _browser_check(html_path, tmp_path)
    assert seen["errors"] == []
    decoded = {alt: width for alt, complete, width in seen["images"] if complete and width > 0}
    assert set(RUN_PLOTS) | {"Responses against quench.time_s"} <= set(decoded)
    assert len(decoded) == len(seen["images"])
    # the probe notices a broken image (so the check above can fail)
    broken = tmp_path / "broken.html"
    broken.write_text(html_path.read_text().replace("</body>", '<img alt="broken" src="data:image/png;base64,AAAA">'
                                                               "</body>"))
    seen = _browser_check(broken, tmp_path)
    assert ["broken", True, 0] in seen["images"] or "IMG" in seen["errors"]
    # and the page paints: the screenshot is not blank
    shot = tmp_path / "shot.png"
    res = _chromium([f"--screenshot={shot}", "--window-size=1200,1600", html_path.as_uri()], tmp_path)
    assert shot.is_file(), res.stderr[-2000:]
    pixels = mpimg.imread(shot)
    assert np.std(pixels[..., :3]) > 0.05
