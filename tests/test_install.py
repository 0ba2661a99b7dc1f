"""A built wheel carries the data it needs: installed outside the checkout it finds its steels and
quenchants (quenchsim/_data) and runs the reference case; the README's bring-your-own-oil and -steel commands and the
guides' (first_hour.md, the data-sheet oil of bring_an_oil.md, shipped names in place of files) work with it, as
written, from a project folder (the wheel is built once for all, ~3-4 minutes in all)."""

import json
import os
import re
import shlex
import shutil
import site
import subprocess
import sys
import sysconfig
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _run(cmd: list[str], cwd: Path, timeout: float) -> subprocess.CompletedProcess:
    # without PYTHONPATH: a checkout on it (PYTHONPATH=. pytest) would be imported instead of the wheel
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    res = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, timeout=timeout, env=env)
    assert res.returncode == 0, f"{' '.join(map(str, cmd))}\n{res.stdout[-2000:]}\n{res.stderr[-2000:]}"
    return res


def running_site_folders() -> list[str]:
    """The site folders of the interpreter running the tests (a venv's own when it runs in one), where numpy,
    scikit-fem, ... are installed: `venv --system-site-packages` would see the base interpreter's instead, which
    lacks them when the tests run in a plain venv (the README's install)."""
    folders = [*site.getsitepackages(), sysconfig.get_paths()["purelib"], sysconfig.get_paths()["platlib"]]
    if site.ENABLE_USER_SITE:
        folders.append(site.getusersitepackages())
    # and the package folders its own .pth files added (a venv that borrows another's packages)
    folders += [f for f in sys.path if Path(f).name in ("site-packages", "dist-packages")]
    return [f for f in dict.fromkeys(folders) if Path(f).is_dir() and ROOT not in Path(f).resolve().parents]


def link_site_folders(venv: Path, folders: list[str]) -> Path:
    """A .pth file in ``venv``'s site-packages that appends ``folders`` to its sys.path (plain paths, so the
    folders' own .pth files -- an editable quenchsim among them -- are not run: the wheel's quenchsim comes
    first and is the only one)."""
    python = venv / "bin" / "python"
    purelib = subprocess.run([str(python), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
                             capture_output=True, text=True, check=True).stdout.strip()
    pth = Path(purelib) / "_quenchsim_test_deps.pth"
    pth.write_text("".join(f"{f}\n" for f in folders))
    return pth


@pytest.fixture(scope="module")
def wheel_venv(tmp_path_factory) -> Path:
    """The wheel built from this checkout and installed (without dependencies) into a new venv that sees the running
    interpreter's site packages for numpy, scikit-fem, ... but no quenchsim other than the wheel's; built once for
    this file's tests."""
    tmp_path = tmp_path_factory.mktemp("wheel")
    wheels = tmp_path / "wheels"
    built = subprocess.run([sys.executable, "-m", "pip", "wheel", "-q", "--no-deps", "-w", str(wheels), str(ROOT)],
                           cwd=tmp_path, capture_output=True, text=True, timeout=600)
    if built.returncode != 0 and "Could not" in built.stderr and "setuptools" in built.stderr:
        pytest.skip(f"the build backend could not be installed here: {built.stderr.strip().splitlines()[-1]}")
    assert built.returncode == 0, built.stderr[-2000:]
    wheel = next(wheels.glob("quenchsim-*.whl"))
    venv = tmp_path / "venv"
    _run([sys.executable, "-m", "venv", str(venv)], tmp_path, 300)
    link_site_folders(venv, running_site_folders())
    _run([str(venv / "bin" / "python"), "-m", "pip", "install", "-q", "--no-deps", "--force-reinstall", str(wheel)],
         tmp_path, 600)
    return venv


def test_built_wheel_runs_the_reference_case_outside_the_checkout(wheel_venv, tmp_path):
    venv, python = wheel_venv, wheel_venv / "bin" / "python"
    where = _run([str(python), "-c", "import quenchsim, quenchsim.materials as m; print(quenchsim.__file__); "
                  "print(m.materials_dir())"], tmp_path, 120).stdout.split()
    assert str(venv) in where[0] and where[1].endswith("_data/materials") and str(venv) in where[1]
    out = tmp_path / "run"
    _run([str(venv / "bin" / "quenchsim"), "run", str(ROOT / "cases" / "crb_outer_ring.toml"), "--condition", "1",
          "--mesh-size", "15", "--set", "quench.time_s=120", "--out", str(out), "--quiet"], tmp_path, 900)
    summary = json.loads((out / "summary.json").read_text())
    assert summary["status"] == "ok" and summary["end_state"]["at_room_temperature"]
    assert summary["dimensions_mm"]["before"]["id"] == pytest.approx(218.3, abs=1e-6)


README_SECTION = "## Your own oil and steel"
README_EXAMPLES = {"my_oil.csv": ROOT / "docs" / "guide" / "first_hour_probe_curve.csv",
                   "data/MY_STEEL.toml": ROOT / "docs" / "guide" / "first_hour_ttt.toml"}
"""The user's files the README's bring-your-own commands read, and the examples it names for them."""


def readme_bring_your_own_commands() -> list[str]:
    """The commands of the README's "Your own oil and steel" section, as written."""
    text = (ROOT / "README.md").read_text()
    section = text[text.index(README_SECTION):]
    section = section[:section.index("\n## ", len(README_SECTION))]
    fences = re.findall(r"^```bash\n(.*?)^```", section, flags=re.MULTILINE | re.DOTALL)
    assert len(fences) == 1, "the section has one ```bash block"
    return [ln.strip() for ln in fences[0].splitlines() if ln.strip()]


def test_readmes_bring_your_own_oil_and_steel_run_from_a_wheel_in_a_project_folder(wheel_venv, tmp_path):
    """The README's commands, exactly, run by the wheel's `quenchsim` in a project folder outside the checkout: the
    fitted oil and steel land in ./materials and the run finds both by name (issue 36)."""
    commands = readme_bring_your_own_commands()
    assert [c.split()[:3] for c in commands] == [["quenchsim", "quenchant", "fit"], ["quenchsim", "material", "fit"],
                                                 ["quenchsim", "run", "crb_outer_ring"]]
    for name, example in README_EXAMPLES.items():
        assert str(example.relative_to(ROOT)) in (ROOT / "README.md").read_text()
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(example, tmp_path / name)
    for command in commands:
        argv = shlex.split(command)
        _run([str(wheel_venv / "bin" / argv[0]), *argv[1:]], tmp_path, 600)
    assert (tmp_path / "materials" / "quenchants" / "my_oil.toml").is_file()
    assert (tmp_path / "materials" / "MY_STEEL.toml").is_file()
    summary = json.loads((tmp_path / "runs" / "mine" / "summary.json").read_text())
    assert summary["status"] == "ok"
    resolved = (tmp_path / "runs" / "mine" / "case.toml").read_text()
    assert 'material = "MY_STEEL"' in resolved and 'quenchant = "my_oil"' in resolved


def _wheel_argv(venv: Path, command: str) -> list[str]:
    argv = shlex.split(command)
    assert argv[0] in ("quenchsim", "python3"), command
    return [str(venv / "bin" / ("quenchsim" if argv[0] == "quenchsim" else "python")), *argv[1:]]


def test_the_guides_commands_run_from_a_wheel_in_a_project_folder(wheel_venv, tmp_path):
    """From a wheel, as written (issue 47): every command of docs/guide/first_hour.md (its example files copied by
    `quenchsim cases copy`, so they are in the wheel), the data-sheet oil of bring_an_oil.md (`--shape-from` by name),
    and shipped names in place of a case file in mesh, bath and bearings runout."""
    from test_first_contact_second_pass import guide_bash_commands
    from test_first_hour import GUIDE, guide_commands

    commands, _ = guide_commands(GUIDE.read_text())
    commands += guide_bash_commands(ROOT / "docs" / "guide" / "bring_an_oil.md", "## From the data-sheet figures")
    commands += ["quenchsim mesh crb_outer_ring --condition 1 --mesh-size 15",
                 "quenchsim bath srb_outer_ring --condition 4",
                 "quenchsim bearings runout runout_695_inner9 --no-plots --json"]
    for command in commands:
        _run(_wheel_argv(wheel_venv, command), tmp_path, 600)
    assert json.loads((tmp_path / "runs" / "mine" / "summary.json").read_text())["status"] == "ok"
    assert (tmp_path / "my_data" / "quenchants" / "NAME.toml").is_file()
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    missing = subprocess.run(_wheel_argv(wheel_venv, "quenchsim run cases/crb_outer_ring.toml --condition 1"),
                             cwd=tmp_path, capture_output=True, text=True, timeout=120, env=env)
    assert missing.returncode == 2 and "give its name, crb_outer_ring" in missing.stderr
