#!/usr/bin/python3
"""Every command's --json on the files of tests/data, from two builds, compared.

A change that moves code or rewrites how outputs are written (tables, generic writers, modules)
must print every number as before. This runs the same command lines with build A and build B and
reports, per command line, whether the JSON is identical (byte for byte), identical apart from
wall times and key order, or different (the keys missing, new and changed), and whether the exit
status and standard error match.

Usage (from the repository root):
    scripts/compare_outputs.py A_BUILD B_BUILD [--out DIR] [--only REGEX] [--timeout 300]
A_BUILD and B_BUILD are build folders (build/release) or frictal executables. Outputs are kept
under DIR (default a temporary folder) as A/NAME.json and B/NAME.json. Exit status 1 where any
command line differs.
"""
import argparse
import json
import pathlib
import re
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent
DATA = "tests/data"
PROFILES = ["profiles/dektak-1.csv", "profiles/csv-2.csv", "profiles/nonuniform.asc", "profiles/xy-1.txt"]
MAPS = ["x3p/ISO5436-sample4.x3p", "x3p/pyramid.x3p", "instruments/di-3.di", "instruments/al3d-1.al3d",
        "x3p/sample-land.x3p"]
# Keys whose values are the machine's time, not the software's answer.
TIMING = re.compile(r"(^|_)(wall|elapsed|cpu)(_|$)|_s$|seconds|per_step")


def cases():
    out = []
    for f in PROFILES:
        name = pathlib.Path(f).stem
        path = f"{DATA}/{f}"
        out += [(f"predict-{name}", ["predict", path, "--quiet"]), (f"signature-{name}", ["signature", path]),
                (f"stats-{name}", ["stats", path]), (f"info-{name}", ["info", path]),
                (f"dimension-{name}", ["dimension", path])]
    out += [("predict-xy-pair", ["predict", f"{DATA}/profiles/xy-1.txt", f"{DATA}/profiles/xy-2.txt", "--quiet"]),
            ("predict-dektak-load",
             ["predict", f"{DATA}/profiles/dektak-1.csv", "--load", "1uN", "--modulus", "70GPa", "--poisson", "0.3",
              "--crop", "0.2mm,0.4mm", "--quiet"]),
            ("tilt-xy-1", ["tilt", "--lower", f"{DATA}/profiles/xy-1.txt"])]
    for f in MAPS:
        name = pathlib.Path(f).stem
        path = f"{DATA}/{f}"
        out += [(f"predict-{name}", ["predict", path, "--quiet"]), (f"stats-{name}", ["stats", path]),
                (f"info-{name}", ["info", path]), (f"anisotropy-{name}", ["anisotropy", path]),
                (f"areal-{name}", ["areal", path])]
    out += [("anisotropy-hold-di-3", ["anisotropy", f"{DATA}/instruments/di-3.di", "--hold"]),
            ("predict-map-pair", ["predict", f"{DATA}/x3p/ISO5436-sample4.x3p", f"{DATA}/instruments/di-3.di",
                                  "--quiet"]),
            ("areal-tilt-predict-only", ["areal-tilt", f"{DATA}/x3p/ISO5436-sample4.x3p", "--predict-only"])]
    out += [(c, [c]) for c in ("settings", "columns", "commands", "warnings", "formats")]
    return out


def executable(build):
    p = pathlib.Path(build)
    if p.is_dir():
        p = p / "apps" / "frictal" / "frictal"
    if not p.is_file():
        sys.exit(f"compare_outputs: {build}: no frictal executable there (expected a build folder or the executable)")
    return str(p.resolve())


def strip(x):
    if isinstance(x, dict):
        return {k: strip(v) for k, v in x.items() if not TIMING.search(k)}
    if isinstance(x, list):
        return [strip(v) for v in x]
    return x


def run(exe, name, argv, outdir, timeout):
    try:
        r = subprocess.run([exe, *argv, "--json"], cwd=ROOT, capture_output=True, text=True, timeout=timeout)
        rc, stdout, stderr = r.returncode, r.stdout, r.stderr
    except subprocess.TimeoutExpired:
        rc, stdout, stderr = "timeout", "", ""
    (outdir / f"{name}.json").write_text(stdout)
    return rc, stdout, stderr


def compare(a, b):
    """'identical', 'same' (apart from timings and key order) or a description of the difference."""
    if a == b:
        return "identical"
    try:
        ja, jb = json.loads(a), json.loads(b)
    except json.JSONDecodeError as e:
        return f"not JSON ({e})"
    sa, sb = strip(ja), strip(jb)
    if sa == sb:
        return "same"
    if isinstance(sa, dict) and isinstance(sb, dict):
        missing = sorted(set(sa) - set(sb))
        new = sorted(set(sb) - set(sa))
        changed = sorted(k for k in set(sa) & set(sb) if sa[k] != sb[k])
        return f"missing {missing[:8]}, new {new[:8]}, changed {changed[:8]}"
    return "different"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("a")
    ap.add_argument("b")
    ap.add_argument("--out", help="folder for the outputs (default: a temporary one)")
    ap.add_argument("--only", help="run only the command lines whose name matches this regular expression")
    ap.add_argument("--timeout", type=float, default=300, help="seconds per command line (default 300)")
    args = ap.parse_args()
    ea, eb = executable(args.a), executable(args.b)
    out = pathlib.Path(args.out or tempfile.mkdtemp(prefix="frictal-compare-"))
    (out / "A").mkdir(parents=True, exist_ok=True)
    (out / "B").mkdir(parents=True, exist_ok=True)
    differ = 0
    rows = [c for c in cases() if not args.only or re.search(args.only, c[0])]
    for name, argv in rows:
        ra, oa, ea_err = run(ea, name, argv, out / "A", args.timeout)
        rb, ob, eb_err = run(eb, name, argv, out / "B", args.timeout)
        verdict = compare(oa, ob)
        notes = []
        if ra != rb:
            notes.append(f"exit {ra} -> {rb}")
        if ea_err != eb_err:
            notes.append("stderr differs")
        bad = verdict not in ("identical", "same") or ra != rb
        differ += bad
        print(f"{'DIFF' if bad else 'ok  '} {name}: {verdict}{'; ' + ', '.join(notes) if notes else ''}", flush=True)
    print(f"{len(rows)} command lines, {differ} differ; outputs in {out}")
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main())
