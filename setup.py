"""Build hook: a wheel (or sdist install) carries the data folders materials/ and cases/ inside the package,
as quenchsim/_data/, so an installed quenchsim finds its steels, quenchants and reference cases without the
repository (quenchsim.shipped.shipped_dir). An editable install reads them from the checkout."""

import shutil
from pathlib import Path

from setuptools import setup
from setuptools.command.build_py import build_py

DATA_FOLDERS = ("materials", "cases")


class BuildPyWithData(build_py):
    def run(self) -> None:
        super().run()
        if getattr(self, "editable_mode", False):
            return
        root = Path(__file__).resolve().parent
        for folder in DATA_FOLDERS:
            shutil.copytree(root / folder, Path(self.build_lib) / "quenchsim" / "_data" / folder, dirs_exist_ok=True,
                            ignore=shutil.ignore_patterns("__pycache__", "*.pyc"))


setup(cmdclass={"build_py": BuildPyWithData})
