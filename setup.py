"""Build hook: a wheel (or sdist install) carries the data folders materials/ and cases/ inside the package,
as quenchsim/_data/ (and the guides' example files as quenchsim/_data/examples), so an installed quenchsim finds its steels, quenchants and reference cases without the
repository (quenchsim.shipped.shipped_dir). An editable install reads them from the checkout."""

import shutil
from pathlib import Path

from setuptools import setup
from setuptools.command.build_py import build_py

DATA_FOLDERS = ("materials", "cases")
EXAMPLES = ("docs/guide", "first_hour_*")
"""The example files the guides name (first_hour_probe_curve.csv, first_hour_ttt.toml), as quenchsim/_data/examples
(quenchsim.shipped.shipped_examples; `quenchsim cases copy NAME` copies one into the user's folder)."""


class BuildPyWithData(build_py):
    def run(self) -> None:
        super().run()
        if getattr(self, "editable_mode", False):
            return
        root = Path(__file__).resolve().parent
        for folder in DATA_FOLDERS:
            shutil.copytree(root / folder, Path(self.build_lib) / "quenchsim" / "_data" / folder, dirs_exist_ok=True,
                            ignore=shutil.ignore_patterns("__pycache__", "*.pyc"))
        examples = Path(self.build_lib) / "quenchsim" / "_data" / "examples"
        examples.mkdir(parents=True, exist_ok=True)
        for path in sorted((root / EXAMPLES[0]).glob(EXAMPLES[1])):
            shutil.copyfile(path, examples / path.name)


setup(cmdclass={"build_py": BuildPyWithData})
