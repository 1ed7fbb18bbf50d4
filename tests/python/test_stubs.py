"""Type stubs: the installed stub equals what the bindings say (regenerated from the installed
module by scripts/gen_stubs.py)."""
import pathlib
import subprocess
import sys

import frictal

ROOT = pathlib.Path(__file__).resolve().parents[2]


def test_installed_stub_matches_the_bindings():
    stub = pathlib.Path(frictal.__file__).parent / "_core.pyi"
    assert stub.exists(), "the package ships no _core.pyi"
    fresh = subprocess.run([sys.executable, str(ROOT / "scripts" / "gen_stubs.py")], check=True,
                           capture_output=True, text=True, cwd="/").stdout
    assert stub.read_text() == fresh, (
        "python/frictal/_core.pyi is stale: regenerate with "
        "PYTHONPATH=build/release/python /usr/bin/python3 scripts/gen_stubs.py > python/frictal/_core.pyi")


def test_stub_is_valid_python():
    import ast

    ast.parse((pathlib.Path(frictal.__file__).parent / "_core.pyi").read_text())
