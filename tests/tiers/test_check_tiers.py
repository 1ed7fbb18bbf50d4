#!/usr/bin/env python3
"""ctest tiers.check: scripts/check-tiers.py passes on the source tree and fails, naming the file,
line and rule, on planted wrong-way includes (a file checked as if it were in src/<module>/).

Usage: test_check_tiers.py SOURCE_DIR
"""
import pathlib
import subprocess
import sys
import tempfile

root = pathlib.Path(sys.argv[1]).resolve()
script = root / "scripts" / "check-tiers.py"


def run(*extra):
    return subprocess.run([sys.executable, str(script), str(root), *extra], capture_output=True, text=True)


failures = []
r = run()
if r.returncode != 0:
    failures.append(f"the source tree does not pass:\n{r.stderr}")

# (module the planted file is in, its include, what the error must say)
planted = [
    ("dem", '#include "frictal/tilt.hpp"',
     "module dem includes frictal/tilt.hpp (public header of tilt), but dem may use only: base, util"),
    ("signature", '#include "frictal/hold.hpp"', "module signature includes frictal/hold.hpp (public header of hold)"),
    ("tilt", '#include "analysis/filter_detail.hpp"',
     "module tilt includes analysis/filter_detail.hpp, a private header of analysis"),
    ("geometry", '#include "study/cache.hpp"', "module geometry includes study/cache.hpp (module study)"),
    ("io", '#include "nothere.hpp"', '"nothere.hpp" is no header of module io'),
    # The models below predict, the experiments not below it: predict may not include the 3D tilt
    # test, and the map model may not include the prediction.
    ("predict", '#include "frictal/areal_tilt.hpp"',
     "module predict includes frictal/areal_tilt.hpp (public header of tilt)"),
    ("maphold", '#include "frictal/predict.hpp"',
     "module maphold includes frictal/predict.hpp (public header of predict)"),
]
with tempfile.TemporaryDirectory() as tmp:
    for module, include, expect in planted:
        f = pathlib.Path(tmp) / f"planted_{module}.cpp"
        f.write_text(f"// planted by tests/tiers/test_check_tiers.py\n{include}\n")
        r = run("--extra", f"{f}={module}")
        where = f"{f}:2: error: "
        if r.returncode == 0:
            failures.append(f"{module}: {include} passed the check")
        elif where + expect not in r.stderr:
            failures.append(f"{module}: {include}: expected\n  {where}{expect}\nin\n{r.stderr}")
        else:
            print(f"fails as it should: {r.stderr.splitlines()[0]}")

if failures:
    print("\n".join(failures), file=sys.stderr)
    sys.exit(1)
print("tiers.check: the tree passes; every planted wrong-way include fails with its file, line and rule")
