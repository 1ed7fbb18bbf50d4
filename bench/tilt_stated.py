#!/usr/bin/python3
"""`frictal tilt` against `frictal predict` on every measured profile of tests/data/profiles.

For each file, runs `frictal predict FILE --json` and `frictal tilt --lower FILE --json --quiet`
with the build's defaults (and with --before BUILD's, a build from before a change, for a
before/after table) and records: the test each states (block length L_b, run-away distance d),
the tilt reading, the model's range that tilt prints (its spread over drops: 5 %, median, 95 %),
predict's median and 5-95 % range, and whether the reading lies inside predict's 5-95 % (within
one tilt increment, tilt_spread_note's tolerance) or carries a warning that says why not
(outside-spread). A file a command refuses is listed with the refusal. Files whose tilt run would
take longer than --timeout seconds are cropped to --crop (a window as `--crop` takes it).

Usage:
  bench/tilt_stated.py [--build build/release] [--before /path/to/old/frictal] [--out FILE.md]
                       [--machine TEXT] [--timeout 30]
"""
import argparse
import datetime
import glob
import json
import os
import platform
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def cli_path(build):
    r = subprocess.run([os.path.join(ROOT, "scripts", "frictal-path"), build], capture_output=True, text=True,
                       check=True)
    return r.stdout.strip()


def run(cli, args, timeout):
    t0 = time.monotonic()
    try:
        r = subprocess.run([cli, *args], capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, f"over {timeout:g} s", timeout
    wall = time.monotonic() - t0
    if r.returncode != 0:
        msg = r.stderr.strip().splitlines()[-1] if r.stderr.strip() else f"exit {r.returncode}"
        return None, msg.split(" (")[0].split(": expected")[0].removeprefix("frictal: "), wall
    return json.loads(r.stdout), "", wall


def fmt(v, digits=4):
    return "-" if v is None else f"{v:.{digits}g}"


def codes(j):
    return [w["code"] for w in j.get("warnings", [])]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default="build/release")
    ap.add_argument("--before", help="a frictal CLI from before the change (its tilt defaults)")
    ap.add_argument("--out", help="write the Markdown table here (default: standard output)")
    ap.add_argument("--machine", default=f"{platform.node()}, {os.cpu_count()} cores")
    ap.add_argument("--timeout", type=float, default=30, help="seconds a run may take before the file is cropped")
    ap.add_argument("--crop", default="0.5mm,0.8mm", help="the window of a file too long to run whole")
    a = ap.parse_args()
    cli = cli_path(a.build)
    files = sorted(glob.glob(os.path.join(ROOT, "tests", "data", "profiles", "*")))
    rows = []
    for path in files:
        name = os.path.basename(path)
        crop = []
        t, err, wall = run(cli, ["tilt", "--lower", path, "--json", "--quiet"], a.timeout)
        if t is None and err.startswith("over"):
            crop = ["--crop", a.crop]
            t, err, wall = run(cli, ["tilt", "--lower", path, *crop, "--json", "--quiet"], a.timeout)
        p, perr, _ = run(cli, ["predict", path, *crop, "--json"], a.timeout)
        row = {"file": name + (f" (crop {a.crop})" if crop else ""), "tilt": t, "tilt_error": err, "wall": wall,
               "predict": p, "predict_error": perr}
        if a.before:
            b, berr, bwall = run(a.before, ["tilt", "--lower", path, *crop, "--json", "--quiet"], 4 * a.timeout)
            row.update(before=b, before_error=berr, before_wall=bwall)
        rows.append(row)
        print(name, "done", file=sys.stderr)
    out = [f"# frictal tilt on measured profiles: the test predict states ({datetime.date.today()})", "",
           f"Machine: {a.machine}. Command: `bench/tilt_stated.py"
           + (" --before OLD" if a.before else "") + "` (tests/data/profiles, each file against itself, "
           "the defaults of both commands). Angles in degrees; `tilt model` is the spread over drops that tilt "
           "prints beside its reading; `inside` is the issue's rule: the reading lies in predict's 5-95 % "
           "(within one tilt increment) or carries a warning that says why not.", ""]
    head = "| file | L_b (m) | d (m) | "
    if a.before:
        head += "before: tilt | before: tilt model q05 / median / q95 | "
    head += "tilt | tilt model q05 / median / q95 | predict median | predict 5-95 % | inside | tilt warnings | wall (s)"
    head += " before / after |" if a.before else " |"
    out += [head, "|" + "---|" * (head.count("|") - 1)]
    for r in rows:
        t, p = r["tilt"], r["predict"]
        cells = [r["file"]]
        if t:
            s = t["surface"]
            cells += [fmt(s.get("block_length_m")), fmt(s.get("runaway_distance_m"))]
        else:
            cells += ["-", "-"]
        if a.before:
            b = r["before"]
            if b:
                cells += [fmt(b["friction_angle_deg"]), " / ".join(fmt(b[k]) for k in (
                    "predicted_spread_q05_deg", "predicted_spread_median_deg", "predicted_spread_q95_deg"))]
            else:
                cells += [f"refused: {r['before_error']}", "-"]
        if t:
            cells += [fmt(t["friction_angle_deg"]), " / ".join(fmt(t[k]) for k in (
                "predicted_spread_q05_deg", "predicted_spread_median_deg", "predicted_spread_q95_deg"))]
        else:
            cells += [f"refused: {r['tilt_error']}", "-"]
        if p:
            cells += [fmt(p["friction_angle_deg"]),
                      f"{fmt(p['friction_angle_q05_deg'])} - {fmt(p['friction_angle_q95_deg'])}"]
        else:
            cells += [f"refused: {r['predict_error']}", "-"]
        if t and p and t["friction_angle_deg"] is not None:
            tol = max(0.1, t["settings"]["tilt_increment"])
            phi = t["friction_angle_deg"]
            inside = p["friction_angle_q05_deg"] - tol <= phi <= p["friction_angle_q95_deg"] + tol
            cells.append("yes" if inside else ("no, warned outside-spread" if "outside-spread" in codes(t)
                                               else "no, NOT warned"))
        else:
            cells.append("-")
        cells += [", ".join(codes(t)) if t else "-",
                  (f"{r['before_wall']:.2g} / " if a.before else "") + f"{r['wall']:.2g}"]
        out.append("| " + " | ".join(cells) + " |")
    text = "\n".join(out) + "\n"
    if a.out:
        with open(a.out, "w", encoding="utf-8") as f:
            f.write(text)
    sys.stdout.write(text)


if __name__ == "__main__":
    main()
