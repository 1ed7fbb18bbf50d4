#!/usr/bin/python3
"""Whole-command benchmark of every user-facing frictal command at the sizes users bring.

For each case (a command line at a size), runs the CLI REPS times and records the median wall time
and the largest peak resident set (the child's ru_maxrss from wait4), then fits the scaling
exponent p of wall ~ size^p over each command's sizes. With --baseline the same cases run on a
second build (A = baseline, B = --build), A and B alternating run by run, and the table gives
B / A: the previous commit's build against this one (`make bench` builds it with bench/build-baseline.sh).
Every finished row is appended to OUT.partial.tsv at once (an interrupted run keeps its rows).

Cases: `signature` (and `--no-hold`) and `predict` of self-affine profile pairs of
10^5, 10^6, 10^7 points (H 0.8, spacing 1 nm, rms 1 um, made by `frictal surface fourier`, so no
numpy is needed); `predict` (the map prediction, the map against itself turned over), `areal`,
`anisotropy` and `report` of self-affine maps of 512^2, 1024^2, 2048^2 nodes (bench/fourier_maps.py,
spacing 1 um, float32 .npy; needs numpy once: --data DIR may hold them made elsewhere); `report`
of the measured pair tests/data/profiles/dektak-1.csv on tests/data/instruments/hfm-1.hfm; the
README's tilt example `tilt koch --iterations 2 --alpha 20`; `contact` of the maps at one load
(about 5 % contact; periodic and padded), a 10-load curve of them (periodic), and of self-affine
profiles of 10^5 and 10^6 points of rms slope about 0.1 at one load (padded), all on 2 threads.

Usage:
  bench/commands.py [--build build/bench] [--baseline build/bench-prev] [--reps 3]
                    [--only signature,predict-map,...] [--max-points 1e7] [--max-map 2048]
                    [--record] [--recorded bench/results/commands.tsv] [--machine TEXT]
Writes bench/results/commands-DATE.md (or --out) and prints each case against the recorded table
(this run / recorded); --record replaces the recorded table with this run.
"""
import argparse
import datetime
import math
import os
import platform
import statistics
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PROFILE_SIZES = [100_000, 1_000_000, 10_000_000]
MAP_SIZES = [512, 1024, 2048]
MAP_SPACING = 1e-6  # m


def profile(data, n, seed):
    return os.path.join(data, f"fourier-H0.8-N{n}-{seed}.x3p")


def contact_profile(data, n):
    """A profile for the contact case: the same spectrum as profile(), rms slope about 0.1."""
    return os.path.join(data, f"fourier-H0.8-N{n}-slope0.1.x3p")


def map_file(data, n):
    return os.path.join(data, f"map-n{n}.npy")


# name -> (sizes, size label, argv(data, size, scratch) without the binary, what it measures)
CASES = {
    "signature": (PROFILE_SIZES, "points", lambda d, n, s: ["signature", profile(d, n, 1), profile(d, n, 2), "--json"],
                  "exact signature + hold-angle analysis (default)"),
    "signature-no-hold": (PROFILE_SIZES, "points",
                          lambda d, n, s: ["signature", profile(d, n, 1), profile(d, n, 2), "--json", "--no-hold"],
                          "exact signature alone"),
    "predict-profile": (PROFILE_SIZES, "points",
                        lambda d, n, s: ["predict", profile(d, n, 1), profile(d, n, 2), "--json", "--quiet"],
                        "the prediction of a profile pair"),
    "predict-map": (MAP_SIZES, "nodes per side",
                    lambda d, n, s: ["predict", map_file(d, n), "--spacing", f"{MAP_SPACING}", "--json", "--quiet"],
                    "the map prediction (5 x 5 drops, free block)"),
    "areal": (MAP_SIZES, "nodes per side",
              lambda d, n, s: ["areal", map_file(d, n), "--spacing", f"{MAP_SPACING}", "--json"],
              "areal signature of the map against itself"),
    "anisotropy": (MAP_SIZES, "nodes per side",
                   lambda d, n, s: ["anisotropy", map_file(d, n), "--spacing", f"{MAP_SPACING}", "--json"],
                   "theta_max over 36 directions"),
    "contact-map": (MAP_SIZES, "nodes per side",
                    lambda d, n, s: ["contact", map_file(d, n), "--spacing", f"{MAP_SPACING}", "--load", "5MPa",
                                     "--modulus", "1GPa", "--poisson", "0", "--periodic", "--threads", "2", "--json"],
                    "elastic contact at one load, about 5 % contact (periodic, 2 threads; with the stiffness)"),
    "contact-map-padded": (MAP_SIZES, "nodes per side",
                           lambda d, n, s: ["contact", map_file(d, n), "--spacing", f"{MAP_SPACING}", "--load", "5MPa",
                                            "--modulus", "1GPa", "--poisson", "0", "--threads", "2", "--json"],
                           "the same, not periodic (padded to 2N - 1 a side, rounded up to 2048 at 1024)"),
    "contact-curve": (MAP_SIZES, "nodes per side",
                      lambda d, n, s: ["contact", map_file(d, n), "--spacing", f"{MAP_SPACING}", "--load",
                                       ",".join(f"{k}MPa" for k in range(1, 11)), "--modulus", "1GPa", "--poisson", "0",
                                       "--periodic", "--threads", "2", "--json"],
                      "a 10-load curve, 1-10 MPa (periodic, 2 threads; warm starts)"),
    "contact-profile": ([100_000, 1_000_000], "points",
                        lambda d, n, s: ["contact", contact_profile(d, n), "--load", "2.5MPa",
                                         "--modulus", "1GPa", "--poisson", "0", "--threads", "2", "--json"],
                        "plane-strain contact of a profile at one load, about 5 % contact (padded, 2 threads)"),
    "report-map": (MAP_SIZES, "nodes per side",
                   lambda d, n, s: ["report", map_file(d, n), "--spacing", f"{MAP_SPACING}", "--quiet",
                                    "-o", os.path.join(s, "report.html")],
                   "the HTML report of a map"),
    "report-pair": ([1], "-",
                    lambda d, n, s: ["report", os.path.join(ROOT, "tests/data/profiles/dektak-1.csv"),
                                     os.path.join(ROOT, "tests/data/instruments/hfm-1.hfm"), "--quiet",
                                     "-o", os.path.join(s, "report.html")],
                    "report of dektak-1.csv on hfm-1.hfm (measured)"),
    "tilt-example": ([1], "-", lambda d, n, s: ["tilt", "koch", "--iterations", "2", "--alpha", "20", "--json"],
                     "README's tilt example (K2, alpha 20 deg)"),
}


def ensure_data(binary, data, cases, sizes_of):
    """Writes the missing inputs: profiles by the CLI, maps by numpy (bench/fourier_maps.py)."""
    os.makedirs(data, exist_ok=True)
    for n in sorted({n for c in cases for n in sizes_of(c) if CASES[c][1] == "points"}):
        for seed in (1, 2):
            path = profile(data, n, seed)
            if not os.path.exists(path):
                length = n * 1e-9
                subprocess.run([binary, "surface", "-o", path, "fourier", "--points", str(n), "--length", f"{length!r}",
                                "--hurst", "0.8", "--rolloff-wavelength", f"{length / 10!r}",
                                "--short-cutoff-wavelength", "4e-9", "--rms-height", "1e-6", "--seed", str(seed)],
                               check=True, stdout=subprocess.DEVNULL)
    for n in sorted({n for c in cases for n in sizes_of(c) if c == "contact-profile"}):
        path = contact_profile(data, n)
        if not os.path.exists(path):
            length = n * 1e-9
            subprocess.run([binary, "surface", "-o", path, "fourier", "--points", str(n), "--length", f"{length!r}",
                            "--hurst", "0.8", "--rolloff-wavelength", f"{length / 10!r}",
                            "--short-cutoff-wavelength", "4e-9", "--rms-height", f"{3e-8 * (n / 1e5) ** 0.8!r}",
                            "--seed", "1"], check=True, stdout=subprocess.DEVNULL)
    for n in sorted({n for c in cases for n in sizes_of(c) if CASES[c][1] == "nodes per side"}):
        path = map_file(data, n)
        if not os.path.exists(path):
            # numpy in a child process: the driver stays small (a child's peak memory counts its
            # parent's at the fork/exec)
            code = ("import sys, numpy as np; sys.path.insert(0, sys.argv[3]); from fourier_maps import fourier_map; "
                    "np.save(sys.argv[1], fourier_map(int(sys.argv[2]), float(sys.argv[4]), seed=1).astype(np.float32))")
            r = subprocess.run([sys.executable, "-c", code, path, str(n), os.path.join(ROOT, "bench"), repr(MAP_SPACING)],
                               capture_output=True, text=True)
            if r.returncode != 0:
                sys.exit(f"bench/commands.py: could not write {path} (numpy needed once; or make the maps elsewhere "
                         f"and pass --data): {r.stderr.strip().splitlines()[-1:]}")


def run_once(binary, argv, timeout, stdout_path=None):
    """(wall s, peak MB, cpu s, error text) of one run; peak and cpu (user + system, all threads)
    are the child's own rusage."""
    t0 = time.perf_counter()
    out = open(stdout_path, "wb") if stdout_path else subprocess.DEVNULL
    p = subprocess.Popen([binary] + argv, stdout=out, stderr=subprocess.PIPE)
    if stdout_path:
        out.close()
    deadline = t0 + timeout
    while True:
        pid, status, ru = os.wait4(p.pid, os.WNOHANG)
        if pid:
            break
        if time.perf_counter() > deadline:
            p.kill()
            pid, status, ru = os.wait4(p.pid, 0)
            return float("inf"), ru.ru_maxrss / 1024, ru.ru_utime + ru.ru_stime, "timeout"
        time.sleep(0.005)
    wall = time.perf_counter() - t0
    p.returncode = os.waitstatus_to_exitcode(status)
    err = p.stderr.read().decode(errors="replace")
    if p.returncode != 0:
        last = err.strip().splitlines()[-1:] or [""]
        return wall, ru.ru_maxrss / 1024, ru.ru_utime + ru.ru_stime, f"exit {p.returncode}: {last[0]}"
    return wall, ru.ru_maxrss / 1024, ru.ru_utime + ru.ru_stime, ""


def fit_exponent(points):
    pts = [(math.log(n), math.log(w)) for n, w in points if w > 0 and math.isfinite(w) and n > 1]
    if len(pts) < 2:
        return float("nan")
    mx = sum(x for x, _ in pts) / len(pts)
    my = sum(y for _, y in pts) / len(pts)
    return sum((x - mx) * (y - my) for x, y in pts) / sum((x - mx) ** 2 for x, _ in pts)


def machine():
    model = "?"
    try:
        for line in subprocess.run(["lscpu"], capture_output=True, text=True).stdout.splitlines():
            if line.startswith("Model name"):
                model = line.split(":", 1)[1].strip()
    except OSError:
        pass
    return f"{model}, {os.cpu_count()} cores, {platform.system()} {platform.release()}"


def read_recorded(path):
    old = {}
    if os.path.exists(path):
        for line in open(path):
            if line.startswith("#") or not line.strip():
                continue
            f = line.rstrip("\n").split("\t")
            old[(f[0], int(f[1]))] = (float(f[2]), float(f[3]), float(f[4]) if len(f) > 4 else math.nan)
    return old


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build", default="build/bench", help="build tree of the CLI under test (B)")
    ap.add_argument("--baseline", help="build tree of the baseline CLI (A), e.g. the previous commit's")
    ap.add_argument("--reps", type=int, default=3, help="runs per case (median wall); 1 for cases over --long s")
    ap.add_argument("--long", type=float, default=60.0, help="a case whose first run takes longer runs once (s)")
    ap.add_argument("--timeout", type=float, default=1800.0, help="per-run limit (s)")
    ap.add_argument("--budget", type=float, default=math.inf,
                    help="whole-run limit (s): the cases not started by then are listed as skipped")
    ap.add_argument("--only", help="comma-separated cases: " + ",".join(CASES))
    ap.add_argument("--max-points", type=float, default=1e7, help="largest profile size")
    ap.add_argument("--max-map", type=int, default=2048, help="largest map (nodes per side)")
    ap.add_argument("--data", default=os.path.join(ROOT, "bench/data/commands"), help="inputs (made when missing)")
    ap.add_argument("--recorded", default=os.path.join(ROOT, "bench/results/commands.tsv"))
    ap.add_argument("--record", action="store_true", help="replace the recorded table with this run")
    ap.add_argument("--machine", help="machine name for the table (default: lscpu model, cores)")
    ap.add_argument("--out", help="Markdown table (default bench/results/commands-DATE.md)")
    a = ap.parse_args()

    def exe(build):
        path = build if os.path.isfile(build) else os.path.join(build, "apps/frictal/frictal")
        if not os.access(path, os.X_OK):
            sys.exit(f"bench/commands.py: no CLI at {path} (build first)")
        return os.path.abspath(path)

    bin_b = exe(a.build)
    bin_a = exe(a.baseline) if a.baseline else None
    cases = a.only.split(",") if a.only else list(CASES)
    for c in cases:
        if c not in CASES:
            sys.exit(f"bench/commands.py: --only: unknown case '{c}' (expected one of {', '.join(CASES)})")

    def sizes_of(c):
        sizes, unit = CASES[c][0], CASES[c][1]
        if unit == "points":
            return [n for n in sizes if n <= a.max_points]
        if unit == "nodes per side":
            return [n for n in sizes if n <= a.max_map]
        return sizes

    ensure_data(bin_b, a.data, cases, sizes_of)
    scratch = os.path.join(a.data, "scratch")
    os.makedirs(scratch, exist_ok=True)
    stamp = datetime.datetime.now(datetime.timezone.utc)
    out_md = a.out or os.path.join(ROOT, f"bench/results/commands-{stamp:%Y-%m-%d}.md")
    partial = out_md + ".partial.tsv"
    mach = a.machine or machine()
    version = subprocess.run([bin_b, "--version"], capture_output=True, text=True).stdout.strip()
    print(f"bench/commands.py: {mach}; B = {bin_b} ({version})" + (f"; A = {bin_a}" if bin_a else ""), flush=True)
    rows = {}  # (case, n) -> {"B": (wall, peak, err, cpu), "A": ...}
    skipped = []
    start = time.perf_counter()
    with open(partial, "w") as pf:
        pf.write("# case\tsize\tbuild\twall_s\tpeak_MB\tcpu_s\terror\n")
        # Smallest sizes of every command first, the largest last (a --budget cuts the largest).
        plan = sorted(((c, n) for c in cases for n in sizes_of(c)),
                      key=lambda cn: (CASES[cn[0]][0].index(cn[1]), cases.index(cn[0])))
        for c, n in plan:
            if time.perf_counter() - start > a.budget or any(
                    k[0] == c and d["B"][2] for k, d in rows.items()):  # out of time, or a smaller size failed
                skipped.append((c, n))
                continue
            argv = CASES[c][2](a.data, n, scratch)
            runs = {"A": [], "B": []}
            reps = a.reps
            r = 0
            while r < reps:
                for tag, binary in (("A", bin_a), ("B", bin_b)):
                    if binary is None:
                        continue
                    w, m, cpu, err = run_once(binary, argv, a.timeout)
                    runs[tag].append((w, m, cpu, err))
                    print(f"  {c:<18} {n:>9}  {tag}  run {r + 1}/{reps}  wall {w:8.2f} s  cpu {cpu:8.2f} s  "
                          f"peak {m:8.0f} MB"
                          + (f"  ({err})" if err else ""), flush=True)
                    if err or w > a.long:
                        reps = 1
                r += 1
            rows[(c, n)] = {}
            for tag, rs in runs.items():
                if not rs:
                    continue
                errs = [e for _, _, _, e in rs if e]
                wall = statistics.median(w for w, _, _, _ in rs)
                peak = max(m for _, m, _, _ in rs)
                cpu = statistics.median(u for _, _, u, _ in rs)
                rows[(c, n)][tag] = (wall, peak, errs[0] if errs else "", cpu)
                pf.write(f"{c}\t{n}\t{tag}\t{wall:.4f}\t{peak:.0f}\t{cpu:.4f}\t{errs[0] if errs else ''}\n")
                pf.flush()

    old = read_recorded(a.recorded)
    lines = [f"# frictal commands: wall time and peak memory ({stamp:%Y-%m-%d %H:%M} UTC)", "",
             f"Machine: {mach}. B: {version}" + (f"; A: {a.baseline}" if bin_a else "") +
             f". Wall: median of up to {a.reps} runs ({'A and B alternating, ' if bin_a else ''}one run when the first "
             f"takes over {a.long:g} s); cpu: user + system time of all threads (median); peak: the largest resident set of the process (wait4). "
             "Produced by bench/commands.py.", ""]
    head = "| command | size | what | wall (s) | cpu (s) | peak (MB) |"
    rule = "|---|---|---|---|---|---|"
    if bin_a:
        head += " A wall (s) | A cpu (s) | A peak (MB) | B/A wall | B/A cpu | B/A memory |"
        rule += "---|---|---|---|---|---|"
    if old:
        head += " / recorded wall | / recorded cpu | / recorded memory |"
        rule += "---|---|---|"
    lines += [head, rule]

    def size_text(c, n):
        unit = CASES[c][1]
        return "-" if unit == "-" else (f"{n:.0e}" if unit == "points" else f"{n}^2")

    for (c, n), d in sorted(rows.items(), key=lambda kv: (cases.index(kv[0][0]), kv[0][1])):
        b = d.get("B")
        cell = f"| {c} | {size_text(c, n)} | {CASES[c][3]} | "
        cell += (f"{b[0]:.2f} | {b[3]:.2f} | {b[1]:.0f} |" if not b[2] else f"failed: {b[2]} | - | {b[1]:.0f} |")
        if bin_a:
            aa = d.get("A")
            cell += (f" {aa[0]:.2f} | {aa[3]:.2f} | {aa[1]:.0f} | {b[0] / aa[0]:.2f} | {b[3] / aa[3]:.2f} | "
                     f"{b[1] / aa[1]:.2f} |") if aa and not aa[2] and not b[2] else " - | - | - | - | - | - |"
        if old:
            o = old.get((c, n))
            cell += f" {b[0] / o[0]:.2f} | {b[3] / o[2]:.2f} | {b[1] / o[1]:.2f} |" if o and not b[2] else " - | - | - |"
        lines.append(cell)
    if skipped:
        lines += ["", "Not run (--budget reached, or a smaller size of the command failed): " +
                  ", ".join(f"{c} {size_text(c, n)}" for c, n in skipped) + "."]
    lines += ["", "Scaling exponent p of wall ~ size^p and of cpu ~ size^p (least squares over the sizes; maps: "
              "size = nodes, i.e. (nodes per side)^2):", ""]
    for c in cases:
        done = [n for n in sizes_of(c) if (c, n) in rows and not rows[(c, n)]["B"][2]]
        size = (lambda n: n * n) if CASES[c][1] == "nodes per side" else (lambda n: n)
        if len(done) >= 2:
            pw = fit_exponent([(size(n), rows[(c, n)]["B"][0]) for n in done])
            pc = fit_exponent([(size(n), rows[(c, n)]["B"][3]) for n in done])
            lines.append(f"- {c}: wall p = {pw:.2f}, cpu p = {pc:.2f}")
    text = "\n".join(lines) + "\n"
    with open(out_md, "w") as f:
        f.write(text)
    print(text)
    if a.record or not old:
        with open(a.recorded, "w") as f:
            f.write(f"# case\tsize\twall_s\tpeak_MB\tcpu_s\t({stamp:%Y-%m-%d %H:%M} UTC; {mach}; {version})\n")
            for (c, n), d in rows.items():
                if not d["B"][2]:
                    f.write(f"{c}\t{n}\t{d['B'][0]:.4f}\t{d['B'][1]:.0f}\t{d['B'][3]:.4f}\n")
        print(f"recorded as {a.recorded}")
    os.remove(partial)
    print(f"wrote {out_md}")
    failed = [k for k, d in rows.items() if d["B"][2]]
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
