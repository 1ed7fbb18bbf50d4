#!/usr/bin/python3
"""Friction under load: the quasi-static tilt test with Hertzian contacts (docs/dem.md sec. 1,
"Hertzian contacts") on profile pairs not tuned on, at several block weights, against the load
prediction of `frictal predict --load W --modulus E --poisson NU` where that option exists, else
against the rigid prediction (said so in the table). Writes bench/results/loaded-tilt.md.

  nice /usr/bin/python3 bench/loaded_tilt.py [BIN] [OUT] [--drops N] [--jobs J] [--loads W,W,..]
      [--radius-factors F,F,..] [--no-convergence]

Pairs: four Fourier-filtered profile pairs (bench/predict_vs_sim_pairs.py's filter; lower 200
points, upper 50, spacing 1 mm / 199, rms slope 0.2; seeds 501-504 not used elsewhere, H 0.8 and
0.6) and one measured pair (two windows of tests/data/profiles/dektak-1.csv, 60 and 20 um). Per
pair, N drops evenly over the prediction's drop range (the drops of predict_vs_sim.sh), per load
W (the upper block's weight, set through its areal density) one `frictal tilt --contact-law hertz
--protocol quasi-static --hold-rotation --block-modulus E --block-poisson NU` from each drop.
Material: E = 70 GPa, nu = 0.3, both blocks of it (E* = E / (2 (1 - nu^2)): `--elastic-blocks 2`,
predict's default). The other settings are the scaled defaults.
Convergence at the middle drop of the first pair at the middle load: the time-step safety factor,
the tilt increment, the spheroradius and the damping ratio halved, the modulus doubled.
--radius-factors: at the loads from 1e-4 N up (where the default spheroradius r is overlapped by a
tenth of itself), the tilt runs are repeated with the spheroradius F r (the Hertz overlap / r falls
as 1 / F at one load), one table row per factor. Predictions are not kept between calls (the
simulations are: they depend on the engine only).
BIN default build/release/apps/frictal/frictal; OUT default /tmp/frictal-loaded-tilt.
"""
import argparse
import hashlib
import json
import os
import platform
import statistics
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from predict_vs_sim_pairs import fourier_profile  # noqa: E402

E, NU = 70e9, 0.3
LOADS = [1e-6, 1e-5, 1e-4, 1e-3, 1e-2]  # upper block weight W (N)
TOL = 0.3  # deg, the rule


def make_pairs(out, repo):
    pairs = []
    n, w, length = 200, 50, 1e-3
    a = length / (n - 1)
    for seed, H in ((501, 0.8), (502, 0.8), (503, 0.6), (504, 0.6)):
        name = f"four{seed}"
        for side, s, m in (("lower", seed, n), ("upper", seed + 1000, w)):
            z = fourier_profile(m, a, s, H=H)
            x = np.arange(m) * a
            z = z - np.polyval(np.polyfit(x, z, 1), x)
            np.savetxt(f"{out}/{name}-{side}.csv", np.column_stack([x, z]), delimiter=",",
                       header="x_m,z_m", comments="")
        pairs.append((name, [f"{out}/{name}-lower.csv", f"{out}/{name}-upper.csv"], ["--detrend", "line"]))
    # The measured pair: the Dektak scan (lateral and height in um) cut into two windows, 100-160 um
    # below and 400-420 um above, written in metres.
    xz = []
    with open(f"{repo}/tests/data/profiles/dektak-1.csv", encoding="latin-1") as f:
        data = False
        for line in f:
            if line.startswith("Lateral um"):
                data = True
                continue
            if data:
                cols = line.split(",")
                try:
                    xz.append((float(cols[0]), float(cols[1])))
                except (ValueError, IndexError):
                    pass
    xz = np.array(xz)
    for side, (x0, x1) in (("lower", (100, 160)), ("upper", (400, 420))):
        w = xz[(xz[:, 0] >= x0) & (xz[:, 0] <= x1)] * 1e-6
        np.savetxt(f"{out}/dektak-{side}.csv", w - [w[0, 0], 0], delimiter=",", header="x_m,z_m", comments="")
    pairs.append(("dektak", [f"{out}/dektak-lower.csv", f"{out}/dektak-upper.csv"], ["--detrend", "line"]))
    return pairs


CACHE = {}
TIMEOUT = 60  # s per run: past the spheroradius a run can relax for minutes (reported as such)


def run(cmd, keep=True):
    # Runs are kept in OUT/runs by their command line: a second call of the script reuses them.
    if not keep:
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0:
            return {"error": (r.stderr or r.stdout).strip().splitlines()[-1:]}
        return json.loads(r.stdout)
    key = hashlib.sha1(" ".join(cmd).encode()).hexdigest()[:16]
    path = f"{CACHE['dir']}/{key}.json"
    if os.path.exists(path):
        return json.load(open(path))
    try:
        r = subprocess.run(cmd, capture_output=True, text=True, timeout=TIMEOUT)
        if r.returncode != 0:
            out = {"error": (r.stderr or r.stdout).strip().splitlines()[-1:]}
        else:
            out = json.loads(r.stdout)
    except subprocess.TimeoutExpired:
        out = {"error": [f"stopped after {TIMEOUT} s"]}
    with open(path, "w") as f:
        json.dump(out, f)
    return out


def predict_cmd(bin_, files, cond, extra):
    return [bin_, "predict", *files, *cond, "--json", "-q", *extra]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("bin", nargs="?", default="build/release/apps/frictal/frictal")
    ap.add_argument("out", nargs="?", default="/tmp/frictal-loaded-tilt")
    ap.add_argument("--drops", type=int, default=7)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--loads", default=",".join(repr(w) for w in LOADS))
    ap.add_argument("--radius-factors", default="1")
    ap.add_argument("--no-convergence", action="store_true")
    args = ap.parse_args()
    loads = [float(w) for w in args.loads.split(",")]
    factors = [float(f) for f in args.radius_factors.split(",")]
    repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    bin_ = os.path.abspath(args.bin)
    os.makedirs(f"{args.out}/runs", exist_ok=True)
    CACHE["dir"] = f"{args.out}/runs"
    t0 = time.time()
    pairs = make_pairs(args.out, repo)
    has_load = "--load" in subprocess.run([bin_, "predict", "--help"], capture_output=True, text=True).stdout
    pool = ThreadPoolExecutor(args.jobs)

    def load_args(W):  # predict's load and material: both blocks of the material, as the tilt's default
        return ["--load", f"{W!r}N", "--modulus", f"{E / 1e9:g}GPa", "--poisson", repr(NU)] if has_load else []

    # The prediction per pair (rigid; and per load where predict takes one), and the drops.
    jobs, preds = [], {}
    for name, files, cond in pairs:
        p = run(predict_cmd(bin_, files, cond, []), keep=False)
        if "error" in p:
            print(name, "predict failed:", p["error"], file=sys.stderr)
            continue
        preds[(name, None)] = p
        for W in loads:
            if has_load:
                preds[(name, W)] = run(predict_cmd(bin_, files, cond, load_args(W)), keep=False)
        lo, hi = p["drop_range_m"][0], p["drop_range_m"][1]
        ra = p["runaway_distance_m"]
        for k in range(args.drops):
            x = lo + (hi - lo) * k / (args.drops - 1)
            for W in loads:
                jobs.append((name, files, cond, k, x, ra, W))

    def tilt(name, files, cond, x, ra, W, extra=(), density=None):
        opts = {"--protocol": "quasi-static", "--runaway-distance": repr(ra), "--contact-law": "hertz",
                "--block-modulus": repr(E), "--block-poisson": repr(NU), "--elastic-blocks": "2"}
        if density is not None:
            opts["--density"] = repr(density)
        opts.update(dict(zip(extra[::2], extra[1::2])))  # a convergence run's changes replace the defaults
        cmd = [bin_, "tilt", "--lower", files[0], "--upper", files[1], *cond, "--hold-rotation",
               f"--initial-offset={x!r}", "--json", "-q"]
        for k, v in opts.items():
            cmd += [k, v]
        return run(cmd)

    # The areal density that makes the upper block weigh W: one run's mass at the default density.
    density, radius = {}, {}
    for name, files, cond in pairs:
        if (name, None) not in preds:
            continue
        p = preds[(name, None)]
        j = tilt(name, files, cond, p["drop_range_m"][0], p["runaway_distance_m"], 0, ("--max-tilt", "0.5"))
        if "error" in j:
            print(name, "tilt failed:", j["error"], file=sys.stderr)
            continue
        rho0 = j["settings"]["density"]
        radius[name] = j["settings"]["spheroradius"]
        for W in loads:
            density[(name, W)] = rho0 * W / (j["upper_mass_kg"] * j["settings"]["gravity"])

    results, drop_preds = {}, {}
    futs, pfuts = {}, {}
    def factors_at(W):  # the default r below 1e-4 N (overlap < 0.1 r there), each factor from it on
        return factors if W >= 1e-4 * (1 - 1e-9) else [1.0]

    for (name, files, cond, k, x, ra, W) in jobs:
        if (name, W) in density:
            for fr in factors_at(W):
                extra = () if fr == 1 else ("--spheroradius", repr(fr * radius[name]))
                futs[(name, k, W, fr)] = pool.submit(tilt, name, files, cond, x, ra, W, extra, density[(name, W)])
            # The prediction from the same drop (per load where predict takes one).
            if has_load or W == loads[0]:
                pfuts[(name, k, W if has_load else None)] = pool.submit(
                    run, predict_cmd(bin_, files, cond, ["--runaway-distance", repr(ra), f"--start-offset={x!r}",
                                                         *load_args(W)]), False)
    # The linear law (rigid limit, the scaled defaults) from the same drops: the ground truth at no load.
    lfuts = {}
    for (name, files, cond, k, x, ra, W) in jobs:
        if W == loads[0] and (name, W) in density:
            lfuts[(name, k)] = pool.submit(tilt, name, files, cond, x, ra, W, ("--contact-law", "linear"))
    linear = {key: f.result() for key, f in lfuts.items()}
    for key, f in futs.items():
        results[key] = f.result()
    for key, f in pfuts.items():
        drop_preds[key] = f.result()

    # Convergence: first pair, middle drop, at a load where the angle does not move with W and at
    # the first where it does.
    name0, files0, cond0 = pairs[0]
    k0 = args.drops // 2
    x0 = next(j[4] for j in jobs if j[0] == name0 and j[3] == k0)
    ra0 = next(j[5] for j in jobs if j[0] == name0)
    conv_loads = [] if args.no_convergence else [LOADS[2], LOADS[3]]
    conv = {}
    for W0 in conv_loads:
        s = results[(name0, k0, W0, 1.0)]["settings"]
        cases = [
            ("time step / 2 (cap and safety factor)", ("--time-step", repr(s["time_step"] / 2),
                                                      "--time-step-safety", repr(s["time_step_safety"] / 2))),
            ("tilt increment / 2", ("--tilt-increment", repr(s["tilt_increment"] / 2))),  # deg
            ("spheroradius / 2", ("--spheroradius", repr(s["spheroradius"] / 2))),
            ("spheroradius x 2", ("--spheroradius", repr(s["spheroradius"] * 2))),
            ("damping ratio / 2", ("--damping-ratio", repr(s["damping_ratio"] / 2))),
            ("modulus x 2", ("--block-modulus", repr(2 * E))),
        ]
        conv[W0] = (s, {label: pool.submit(tilt, name0, files0, cond0, x0, ra0, W0, extra, density[(name0, W0)])
                        for label, extra in cases})
    conv = {W0: (s, {label: f.result() for label, f in c.items()}) for W0, (s, c) in conv.items()}
    wall = time.time() - t0

    # Tables.
    lines = []
    out = lines.append
    cpu = "unknown CPU"
    try:
        cpu = next(l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name"))
    except (OSError, StopIteration):
        pass
    commit = subprocess.run(["git", "-C", repo, "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip()
    sim_wall = sum(json.load(open(f"{CACHE['dir']}/{f}")).get("wall_time_s", 0) for f in os.listdir(CACHE["dir"]))
    out(f"Measured {time.strftime('%Y-%m-%d', time.gmtime())} at commit {commit} on {os.cpu_count()} cores "
        f"({cpu}, {platform.system()}, load {os.getloadavg()[0]:.1f}), {args.drops} drops per pair and load, "
        f"{len(os.listdir(CACHE['dir']))} runs, {sim_wall:.0f} s of time stepping in all (runs stopped at "
        f"{TIMEOUT} s not counted; this call {wall:.0f} s wall, runs kept from an earlier call reused): "
        "`nice /usr/bin/python3 bench/loaded_tilt.py`.")
    out("")
    ref = "`frictal predict --load W --modulus E --poisson NU`" if has_load else \
        "the rigid `frictal predict` (this build's predict has no --load: the load model is not compared)"
    out(f"Compared with {ref}; E = {E:.3g} Pa, nu = {NU}, both blocks elastic, E* = E / (2 (1 - nu^2)). Angles in degrees; the "
        "simulated median and 5-95 % over the drops; `rule`: |simulated median - predicted median| <= "
        f"{TOL} deg or the simulated median inside the prediction's q05-q95.")
    out("")
    out("Columns: contacts and mean overlap / R at the end of settling (median over the drops); max "
        "overlap / r the largest resting overlap over the spheroradius; predicted median: of the "
        "predictions from the same drops; `predict` q50 (q05-q95): the prediction over its own drops.")
    out("")
    out("| pair | W (N) | r | contacts | mean overlap / R | max overlap / r | drops slid | simulated median | "
        "simulated q05-q95 | linear law (rigid limit) median | predicted median | `predict` q50 (q05-q95) | "
        "difference | rule | warnings |")
    out("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    summary = []
    for name, files, cond in pairs:
        for W in loads:
            for fr in factors_at(W):
                runs = [results.get((name, k, W, fr)) for k in range(args.drops)]
                runs = [r for r in runs if r is not None]
                if not runs:
                    continue
                ok = [r for r in runs if "error" not in r and r.get("slid")]
                errs = [r for r in runs if "error" in r]
                angles = [r["friction_angle_deg"] for r in ok]
                p = preds.get((name, W) if has_load else (name, None))
                if p is None or "error" in p:
                    p = preds[(name, None)]
                pq50 = p.get("friction_angle_q50_deg", p["friction_angle_deg"])
                p5, p95 = p["friction_angle_q05_deg"], p["friction_angle_q95_deg"]
                dp = [drop_preds.get((name, k, W if has_load else None)) for k in range(args.drops)]
                dp = [d["friction_angle_deg"] for d in dp if d and "error" not in d]
                pm = statistics.median(dp) if dp else pq50
                good = [r for r in runs if "error" not in r]
                nc = statistics.median([r["settled_contacts"] for r in good]) if good else float("nan")
                ir = [r["settled_interference_ratio"] for r in good if r.get("settled_interference_ratio") is not None]
                ovr = [r["settled_overlap_m"] / r["settings"]["spheroradius"] for r in good]
                codes = sorted({w["code"] for r in good for w in r["warnings"]})
                if errs:
                    codes.append(f"{len(errs)} failed: {errs[0]['error'][0][:80] if errs[0]['error'] else ''}")
                lin = [linear.get((name, k)) for k in range(args.drops)]
                lin = [r["friction_angle_deg"] for r in lin if r and "error" not in r and r.get("slid")]
                lmed = f"{statistics.median(lin):.3f}" if lin else "-"
                rl = "r" if fr == 1 else f"{fr:g} r"
                if angles:
                    med = statistics.median(angles)
                    q = np.percentile(angles, [5, 95])
                    diff = med - pm
                    rule = "pass" if abs(diff) <= TOL or p5 <= med <= p95 else "FAIL"
                    summary.append((name, W, fr, rule, diff))
                    out(f"| {name} | {W:.0e} | {rl} | {nc:.0f} | "
                        f"{statistics.median(ir) if ir else float('nan'):.2e} | {max(ovr):.3f} | "
                        f"{len(ok)} / {len(runs)} | {med:.3f} | {q[0]:.2f}-{q[1]:.2f} | {lmed} | {pm:.3f} | "
                        f"{pq50:.2f} ({p5:.2f}-{p95:.2f}) | {diff:+.3f} | {rule} | {', '.join(codes) or '-'} |")
                else:
                    out(f"| {name} | {W:.0e} | {rl} | {nc:.0f} | - | - | 0 / {len(runs)} | - | - | {lmed} | "
                        f"{pm:.3f} | {pq50:.2f} ({p5:.2f}-{p95:.2f}) | - | - | {', '.join(codes) or '-'} |")
    out("")
    out("Per drop (degrees): simulated / predicted from the same drop, drops 0..N-1.")
    out("")
    out("| pair | W (N) | r | drops: simulated / predicted |")
    out("|---|---|---|---|")
    for name, files, cond in pairs:
        for W in loads:
            for fr in factors_at(W):
                cells = []
                for k in range(args.drops):
                    r = results.get((name, k, W, fr))
                    d = drop_preds.get((name, k, W if has_load else None))
                    a = f"{r['friction_angle_deg']:.2f}" if r and "error" not in r and r.get("slid") else "-"
                    b = f"{d['friction_angle_deg']:.2f}" if d and "error" not in d else "-"
                    cells.append(f"{a} / {b}")
                out(f"| {name} | {W:.0e} | {'r' if fr == 1 else f'{fr:g} r'} | {'; '.join(cells)} |")
    out("")
    for W0, (s, cases) in conv.items():
        base = results[(name0, k0, W0, 1.0)]
        out(f"Convergence: {name0}, drop {k0} (offset {x0 * 1e6:.2f} um), W = {W0:.0e} N (degrees):")
        out("")
        out("| run | friction angle | change | max overlap / r | steps | wall s | warnings |")
        out("|---|---|---|---|---|---|---|")

        def row(label, j):
            if "error" in j:
                out(f"| {label} | failed: {j['error']} | | | | | |")
                return
            a = j["friction_angle_deg"] if j.get("slid") else float("nan")
            b = base["friction_angle_deg"] if base.get("slid") else float("nan")
            out(f"| {label} | {a:.3f} | {a - b:+.3f} | {j['settled_overlap_m'] / j['settings']['spheroradius']:.3f} | "
                f"{j['steps']} | {j['wall_time_s']:.2f} | "
                f"{', '.join(sorted({w['code'] for w in j['warnings']})) or '-'} |")
        row(f"defaults (r = {s['spheroradius']:.3g} m, increment {s['tilt_increment']:.3g} deg, time step cap "
            f"{s['time_step']:.3g} s, safety {s['time_step_safety']}, zeta {s['damping_ratio']})", base)
        for label, j in cases.items():
            row(label, j)
        out("")
    text = "\n".join(lines)
    print(text)
    with open(f"{args.out}/loaded-tilt-tables.md", "w") as f:
        f.write(text + "\n")


if __name__ == "__main__":
    main()
