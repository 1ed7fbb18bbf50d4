"""The package under test is the installed one (pip into a venv), with its version and types."""
import os
import pathlib

import frictal


def test_imported_from_the_installation():
    prefix = os.environ.get("FRICTAL_EXPECT_INSTALLED")
    if prefix:  # set by CTest: pytest must not pick up a build tree or the source tree
        assert pathlib.Path(frictal.__file__).resolve().is_relative_to(pathlib.Path(prefix).resolve())


def test_version_is_the_projects():
    # The version is defined once (CMakeLists.txt project(VERSION)); the package reports it.
    root = pathlib.Path(__file__).resolve().parents[2]
    text = (root / "CMakeLists.txt").read_text(encoding="utf-8")
    import re

    declared = re.search(r"project\(\s*frictal\s+VERSION\s+([0-9.]+)", text).group(1)
    assert frictal.__version__ == declared


def test_typed_package():
    pkg = pathlib.Path(frictal.__file__).parent
    assert (pkg / "py.typed").exists()
