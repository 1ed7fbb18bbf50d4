#!/usr/bin/python3
"""Builds frictal's documentation site (`make docs`): BUILD_DIR/../docs/html by default.

    scripts/docs/build.py [--build BUILD_DIR] [--out OUT_DIR] [--jobs N]

Offline, from Debian's packages only (scripts/install-deps), with Sphinx warnings as errors:
  1. stages docs/site/ (pages, notebooks, conf.py) with the Markdown guides of docs/ into OUT/src;
  2. generates the reference pages from the built frictal (scripts/docs/gen_reference.py): the
     CLI from `frictal commands --json`, the settings tables, the formats and the instrument files
     of tests/data/instruments, the study task kinds, the C++ header list;
  3. runs Doxygen on include/frictal/ (XML for Breathe);
  4. copies the part of Debian's MathJax that the pages use into _static (no CDN);
  5. runs sphinx-build -W: the notebooks are executed with the built Python module.
Prints the time each step took.
"""
import argparse
import os
import shutil
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
# The Markdown guides of docs/ that the site shows as pages (docs/settings.md is regenerated).
GUIDES = ["ARCHITECTURE.md", "STYLE.md", "analysis.md", "contact.md", "load.md", "dem.md", "io.md", "mujoco.md", "performance.md", "report.md",
          "studies.md"]
MATHJAX = "/usr/share/javascript/mathjax"
MATHJAX_PARTS = ["MathJax.js", "config/TeX-AMS_CHTML.js", "extensions", "jax/input/TeX", "jax/output/CommonHTML",
                 "jax/element", "localization/en", "fonts/HTML-CSS/TeX/woff"]

DOXYFILE = """
PROJECT_NAME = frictal
INPUT = {root}/include/frictal
FILE_PATTERNS = *.hpp
OUTPUT_DIRECTORY = {out}
GENERATE_XML = YES
GENERATE_HTML = NO
GENERATE_LATEX = NO
EXTRACT_ALL = YES
EXTRACT_STATIC = NO
EXTRACT_PRIVATE = NO
HIDE_UNDOC_RELATIONS = YES
EXCLUDE_SYMBOLS = detail detail::* *_detail *_detail::*
MACRO_EXPANSION = YES
ENABLE_PREPROCESSING = YES
JAVADOC_AUTOBRIEF = NO
QUIET = YES
WARN_IF_UNDOCUMENTED = NO
WARN_AS_ERROR = NO
WARN_LOGFILE = {out}/doxygen-warnings.log
STRIP_FROM_PATH = {root}/include
"""


def step(name, t0):
    print(f"docs: {name} ({time.time() - t0:.1f} s)", flush=True)
    return time.time()


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=os.path.join(ROOT, "build", "release"), help="frictal's CMake build tree")
    ap.add_argument("--out", default=os.path.join(ROOT, "build", "docs"), help="output folder (html/ inside)")
    ap.add_argument("--jobs", default="1", help="sphinx-build -j (notebooks run one at a time)")
    args = ap.parse_args()
    build = os.path.abspath(args.build)
    out = os.path.abspath(args.out)
    cli_rel = subprocess.run([os.path.join(ROOT, "scripts", "frictal-path"), build], capture_output=True, text=True,
                             check=True).stdout.strip()
    cli = cli_rel if os.path.isabs(cli_rel) else os.path.join(ROOT, cli_rel)
    pydir = os.path.join(build, "python")
    for need, what in [(cli, "the frictal CLI"), (os.path.join(pydir, "frictal", "__init__.py"), "the Python module")]:
        if not os.path.exists(need):
            sys.exit(f"docs: {what} is not built ({need}); run `make build` first")
    try:
        import sphinx  # noqa: F401
    except ImportError:
        sys.exit("docs: Sphinx is missing; run scripts/install-deps (Debian's python3-sphinx and friends)")

    t_start = t0 = time.time()
    src = os.path.join(out, "src")
    shutil.rmtree(src, ignore_errors=True)
    shutil.copytree(os.path.join(ROOT, "docs", "site"), src, ignore=shutil.ignore_patterns("__pycache__", ".ipynb*"))
    os.makedirs(os.path.join(src, "guide"), exist_ok=True)
    for g in GUIDES:
        shutil.copy(os.path.join(ROOT, "docs", g), os.path.join(src, "guide", g))
    shutil.copytree(os.path.join(ROOT, "docs", "images"), os.path.join(src, "guide", "images"))
    env = dict(os.environ)
    env["PYTHONPATH"] = pydir + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    env["FRICTAL_CLI"] = cli
    env["FRICTAL_SOURCE_DIR"] = ROOT
    env.setdefault("OMP_NUM_THREADS", "1")
    env["PYDEVD_DISABLE_FILE_VALIDATION"] = "1"  # ipykernel's debugger note on frozen modules, not ours
    t0 = step("staged docs/site and the guides", t0)

    subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "docs", "gen_reference.py"), "--cli", cli, "--out",
                    src], check=True, env=env)
    t0 = step("generated the reference pages from the built frictal", t0)

    dox = os.path.join(out, "doxygen")
    shutil.rmtree(dox, ignore_errors=True)
    os.makedirs(dox)
    with open(os.path.join(dox, "Doxyfile"), "w") as f:
        f.write(DOXYFILE.format(root=ROOT, out=dox))
    subprocess.run(["doxygen", os.path.join(dox, "Doxyfile")], check=True, cwd=dox)
    env["FRICTAL_DOXYGEN_XML"] = os.path.join(dox, "xml")
    t0 = step("doxygen XML of include/frictal", t0)

    mj = os.path.join(src, "_static", "mathjax")
    for part in MATHJAX_PARTS:
        s, d = os.path.join(MATHJAX, part), os.path.join(mj, part)
        os.makedirs(os.path.dirname(d), exist_ok=True)
        (shutil.copytree if os.path.isdir(s) else shutil.copy)(s, d)
    t0 = step("MathJax (Debian's libjs-mathjax) copied for offline pages", t0)

    html, doctrees = os.path.join(out, "html"), os.path.join(out, "doctrees")
    # Always from scratch: a cached doctree would skip a page's warnings and a notebook's run.
    shutil.rmtree(html, ignore_errors=True)
    shutil.rmtree(doctrees, ignore_errors=True)
    cmd = [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html", "-j", args.jobs, "-d", doctrees,
           src, html]
    r = subprocess.run(cmd, env=env, cwd=src)
    if r.returncode != 0:
        sys.exit(f"docs: sphinx-build failed (exit {r.returncode})")
    # The executed notebooks (outputs included) beside their pages: what a reader downloads to see
    # the results without running them, and what the docs.check test reads.
    executed = os.path.join(doctrees, "nbsphinx", "tutorials")
    for nb in sorted(os.listdir(executed)):
        if nb.endswith(".ipynb"):
            shutil.copy(os.path.join(executed, nb), os.path.join(html, "tutorials", nb))
    t0 = step("sphinx-build -W (notebooks executed)", t0)
    print(f"docs: built {html}/index.html in {time.time() - t_start:.0f} s")


if __name__ == "__main__":
    main()
