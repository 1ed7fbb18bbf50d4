#!/usr/bin/python3
"""Plots the paper's figures from frictal study stores (SQLite, schema of docs/studies.md).

    scripts/plot_studies.py OUTDIR [--fig06 S.sqlite] [--fig07 S.sqlite] [--fig08 S.sqlite]
                                   [--fig09 S.sqlite] [--fig10 S.sqlite] [--fig14-18 S.sqlite]

Only the standard library, numpy and matplotlib: it reads the stores directly, so it works on a
store copied from a cluster without a frictal build.
"""
import argparse
import collections
import json
import sqlite3
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def tasks(path, part_prefix=None):
    """Done tasks as (part, params dict, scalars dict, task_id)."""
    con = sqlite3.connect(f"file:{path}?mode=ro", uri=True)
    rows = con.execute("SELECT task_id, part, params, scalars FROM tasks WHERE status = 'done'").fetchall()
    out = []
    for tid, part, params, scalars in rows:
        if part_prefix and not part.startswith(part_prefix):
            continue
        out.append((part, json.loads(params), json.loads(scalars or "{}"), tid))
    con.close()
    return out


def arrays(path, task_id):
    con = sqlite3.connect(f"file:{path}?mode=ro", uri=True)
    res = {name: np.array([np.nan if v is None else v for v in json.loads(js)])
           for name, js in con.execute("SELECT name, json FROM arrays WHERE task_id = ?", (task_id,))}
    con.close()
    return res


def fig06(store, out):
    fig, ax = plt.subplots(figsize=(6, 4.5))
    colors = {0: "C0", 1: "C1", 2: "C2", 3: "C3"}
    theory = collections.defaultdict(dict)
    for part, p, s, _ in tasks(store, "theory"):
        theory[p["iterations"]][p["alpha"]] = s["friction_angle_deg"]
    for n, m in sorted(theory.items()):
        a = sorted(m)
        ax.plot(a, [m[x] for x in a], "-", color=colors.get(n), label=f"K{n} theory (signature)")
    sim = collections.defaultdict(dict)
    for part, p, s, _ in tasks(store, "simulation"):
        sim[p["iterations"]][p["alpha"]] = s["friction_angle_deg"]
    for n, m in sorted(sim.items()):
        a = sorted(m)
        ax.plot(a, [m[x] for x in a], "o", mfc="none", color=colors.get(n), label=f"K{n} simulation")
    ax.set_xlabel("α (deg)")
    ax.set_ylabel("friction angle φ (deg)")
    ax.set_title("Fig. 6: friction angle vs α, μ_a = 0")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(f"{out}/fig06.png", dpi=120)


def fig07(store, out):
    fig, ax = plt.subplots(figsize=(6, 4.5))
    for part, p, s, tid in sorted(tasks(store), key=lambda t: t[1].get("iterations", 0)):
        a = arrays(store, tid)
        if "displacement_over_length" not in a:
            continue
        ax.plot(a["displacement_over_length"], a["force_angle_over_alpha"], lw=0.8, label=f"K{p['iterations']}")
    ax.set_ylim(-4, 4)  # bounces (F_n near 0) send the ratio far off; the paper's range
    ax.set_xlabel("relative displacement / L_b")
    ax.set_ylabel("atan(F_t/F_n) / α")
    ax.set_title("Fig. 7: force angle during the tilt test, α = 20°")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(f"{out}/fig07.png", dpi=120)


def fig08(store, out):
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4.5))
    mult = {0: 1, 1: 1, 2: 2, 3: 3}
    th = collections.defaultdict(list)
    for part, p, s, _ in tasks(store, "theory"):
        if p["iterations"] == 1:
            th[p["alpha"]].append((np.degrees(np.arctan(p["atomic_friction"])), s["friction_angle_deg"]))
    for alpha, pts in sorted(th.items()):
        pts.sort()
        a1.plot(*zip(*pts), "-", lw=1, label=f"theory α = {alpha:g}°")
    xs, ys = [], []
    for part, p, s, _ in tasks(store, "simulation"):
        ta = s["atomic_friction_angle_deg"]
        if p["iterations"] == 1:
            a1.plot(ta, s["friction_angle_deg"], "o", mfc="none", color="k")
        xs.append(ta)
        ys.append(s["friction_angle_deg"] - mult[p["iterations"]] * p["alpha"])
    a1.set_xlabel("θ_a (deg)")
    a1.set_ylabel("φ (deg)")
    a1.set_title("Fig. 8a: K1, simulation (o) and φ = θ_a + α")
    a1.legend(fontsize=7)
    a2.plot(xs, ys, "o", mfc="none")
    lim = [0, max(xs + [45])]
    a2.plot(lim, lim, "k-", lw=0.8, label="φ - nα = θ_a")
    a2.set_xlabel("θ_a (deg)")
    a2.set_ylabel("φ - nα (deg)")
    a2.set_title("Fig. 8b: all simulations collapse")
    a2.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(f"{out}/fig08.png", dpi=120)


def fig09(store, out):
    fig, ax = plt.subplots(figsize=(6, 4.5))
    best = None
    for part, p, s, tid in sorted(tasks(store), key=lambda t: t[1]["iterations"]):
        a = arrays(store, tid)
        lam = p.get("wavelength", 0.01)
        ax.loglog(a["ruler_m"] / lam, a["measured_length_m"] / lam, "o-", ms=3, lw=0.8,
                  label=f"K{p['iterations']}: D = {s['dimension']:.4f}")
        best = (a, s, lam)
    if best:
        a, s, lam = best
        eps = a["ruler_m"] / lam
        k = int(np.argmax(eps))  # anchor at the largest ruler, where every iteration agrees
        ref = a["measured_length_m"][k] / lam * (eps / eps[k]) ** (1 - s["dimension_eq13"])
        ax.loglog(eps, ref, "k--", lw=1, label=f"Eq. 13: D = {s['dimension_eq13']:.4f}")
    ax.set_xlabel("ruler ε / λ")
    ax.set_ylabel("measured length L / λ")
    ax.set_title("Fig. 9: divider method on Koch curves")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(f"{out}/fig09.png", dpi=120)


def fig10(store, out):
    fig, ax = plt.subplots(figsize=(6, 4.5))
    d13 = {}
    theory = collections.defaultdict(list)
    for part, p, s, _ in tasks(store, "theory"):
        d13[p["alpha"]] = s["dimension_eq13"]
        theory[p["iterations"]].append((s["dimension_eq13"], s["friction_coefficient"]))
    for n, pts in sorted(theory.items()):
        pts.sort()
        ax.plot(*zip(*pts), "-", color=f"C{n}", label=f"K{n} theory")
    for part, p, s, _ in tasks(store, "simulation"):
        if p["alpha"] in d13:
            ax.plot(d13[p["alpha"]], s["friction_coefficient"], "o", mfc="none", color=f"C{p['iterations']}")
    ax.set_xlabel("fractal dimension D (Eq. 13)")
    ax.set_ylabel("μ")
    ax.set_title("Fig. 10: μ against D (lines: theory, o: simulation)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(f"{out}/fig10.png", dpi=120)


def fig14_18(store, out):
    acc = collections.defaultdict(lambda: collections.defaultdict(list))
    for part, p, s, _ in tasks(store):
        key = (round(p["dimension"], 6), p["n_max"])
        for name in ("tan_contact_slope_max", "tan_surface_slope_max", "contact_slope_std_deg", "surface_slope_std_deg"):
            acc[name][key].append(s[name])
    Ds = sorted({k[0] for k in acc["tan_contact_slope_max"]})
    ns = sorted({k[1] for k in acc["tan_contact_slope_max"]})
    mean = {name: {k: float(np.mean(v)) for k, v in d.items()} for name, d in acc.items()}

    def panel(ax, name, dsel, title):
        for D in dsel:
            ax.plot(ns, [mean[name].get((D, n), np.nan) for n in ns], "o-", ms=3, lw=1, label=f"D = {D:g}")
        ax.set_xlabel("n_max")
        ax.set_title(title, fontsize=9)
        ax.legend(fontsize=6)

    lo = [D for D in Ds if D <= 1.5]
    hi = [D for D in Ds if D >= 1.5]
    for fig_name, (sname, cname, ylabel) in {
        "fig14": ("tan_surface_slope_max", "tan_contact_slope_max", "tan θ_max"),
        "fig17": ("surface_slope_std_deg", "contact_slope_std_deg", "σ (deg)"),
    }.items():
        fig, axes = plt.subplots(2, 2, figsize=(9, 7))
        panel(axes[0, 0], sname, lo, "surface slope, D ≤ 1.5")
        panel(axes[0, 1], sname, hi, "surface slope, D ≥ 1.5")
        panel(axes[1, 0], cname, lo, "contact slope, D ≤ 1.5")
        panel(axes[1, 1], cname, hi, "contact slope, D ≥ 1.5")
        for ax in axes.ravel():
            ax.set_ylabel(ylabel)
        fig.suptitle(f"{'Fig. 14: maximum' if fig_name == 'fig14' else 'Fig. 17: standard deviation of'} slopes of WM pairs (mean over pairs)")
        fig.tight_layout()
        fig.savefig(f"{out}/{fig_name}.png", dpi=120)
    nm = max(ns)
    for fig_name, (sname, cname, ylabel, title) in {
        "fig15": ("tan_surface_slope_max", "tan_contact_slope_max", "tan θ_max", "Fig. 15: maximum slopes"),
        "fig18": ("surface_slope_std_deg", "contact_slope_std_deg", "σ (deg)", "Fig. 18: standard deviations"),
    }.items():
        fig, ax = plt.subplots(figsize=(6, 4.5))
        ax.plot(Ds, [mean[sname].get((D, nm), np.nan) for D in Ds], "s-", label="surface slope")
        ax.plot(Ds, [mean[cname].get((D, nm), np.nan) for D in Ds], "o-", label="contact slope")
        ax.set_xlabel("D")
        ax.set_ylabel(ylabel)
        ax.set_title(f"{title} vs D, n_max = {nm}")
        ax.legend()
        fig.tight_layout()
        fig.savefig(f"{out}/{fig_name}.png", dpi=120)


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("outdir")
    ap.add_argument("--fig06")
    ap.add_argument("--fig07")
    ap.add_argument("--fig08")
    ap.add_argument("--fig09")
    ap.add_argument("--fig10")
    ap.add_argument("--fig14-18", dest="fig14_18")
    a = ap.parse_args(argv)
    done = []
    for name, fn in (("fig06", fig06), ("fig07", fig07), ("fig08", fig08), ("fig09", fig09), ("fig10", fig10),
                     ("fig14_18", fig14_18)):
        store = getattr(a, name)
        if store:
            try:
                fn(store, a.outdir)
            except (sqlite3.Error, KeyError, ValueError) as e:
                print(f"plot_studies: {name}: cannot plot {store}: {e}", file=sys.stderr)
                return 2
            done.append(name)
    print("plot_studies: wrote " + ", ".join(done) + f" under {a.outdir}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
