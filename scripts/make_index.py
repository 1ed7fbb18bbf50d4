#!/usr/bin/python3
"""Writes OUTDIR/index.html: one verdict per claim of the paper that frictal checks (supported, not
supported with its measured cause, or superseded by frictal's own finding), frictal's own findings,
and every figure of the paper that frictal computes beside its numbers. One self-contained page
(images embedded).

    scripts/make_index.py BIN OUTDIR [--quick]

BIN is the frictal executable. The findings and conclusions are data: OUTDIR/studies/findings.json,
written by `frictal study report --json` over every store (scripts/reproduce; asked of BIN here when
it is missing). The figures that the studies draw (scripts/plot_studies.py: OUTDIR/fig06.png ...)
and Fig. 4 (OUTDIR/fig04/) are taken as scripts/reproduce left them; the figures beyond the paper
are drawn from the tables `frictal study export --csv` wrote (OUTDIR/studies/STUDY/PART.csv).
Figures 3, 5, 11, 12, 13 and 16 are computed here with BIN (under OUTDIR/index/), and the claims
checked on them join the conclusions. A figure whose inputs are missing is listed as not produced
(never a broken image). The standard library, numpy, matplotlib and frictal's Python package
(BIN's build's, for the DEM frames file).
"""
import argparse
import base64
import csv
import glob
import html
import io
import json
import math
import os
import re
import subprocess
import sys

import matplotlib
import matplotlib.ticker

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.patches import Circle, Polygon  # noqa: E402

DPI = 110


class Figure:
    def __init__(self, number, title, claim):
        self.number, self.title, self.claim = number, title, claim
        self.png = None          # bytes
        self.numbers = []        # (name, value) rows
        self.verdicts = []       # checked here: (supported: bool, text, criterion[, claim id])
        self.conclusions = []    # the claims that speak to it (`frictal study report --json`)
        self.studies = set()     # the studies named after it
        self.missing = None      # why the figure is not on the page
        self.source = ""         # how it was computed


def run(bin_, *args, check=True):
    r = subprocess.run([bin_, *map(str, args)], capture_output=True, text=True)
    if check and r.returncode != 0:
        raise RuntimeError(f"{bin_} {' '.join(map(str, args))}: exit {r.returncode}: {r.stderr.strip()}")
    return r.stdout


# The surfaces here are generated (the paper's): every analysis of their files reads them as
# generated, --detrend none (the CLI removes a file's line by default).
def run_json(bin_, *args):
    return json.loads(run(bin_, *args))


def read_xz(path):
    d = np.genfromtxt(path, delimiter=",", names=True)
    return d["x_m"], d["z_m"]


def png_bytes(fig):
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=DPI)
    plt.close(fig)
    return buf.getvalue()


def slopes_deg(x, z):
    dx = np.diff(x)
    ok = dx > 0
    return np.degrees(np.arctan(np.diff(z)[ok] / dx[ok])), dx[ok]


# ---------------------------------------------------------------------------------------------
# Figures computed here

def fig03(bin_, work):
    f = Figure(3, "Koch surfaces K0–K3",
               "The triadic Koch surface K_n replaces the middle third of every segment of K_(n-1) by an outward "
               "isosceles triangle of base angle α, starting from a row of triangles K_0 (Sec. III). Its steepest "
               "edge is (n+1)α, and each iteration multiplies the curve's length by (2 + 1/cos α)/3 (two thirds "
               "kept, the middle third replaced by two sides of length 1/(6 cos α)).")
    alpha = 20.0
    fig, axes = plt.subplots(4, 1, figsize=(7.5, 6.2), sharex=True)
    ok_slope, ok_len, lengths = True, True, []
    for n, ax in enumerate(axes):
        path = f"{work}/k{n}-curve.csv"
        run(bin_, "surface", "koch", "--iterations", n, "--alpha", alpha, "--wavelength", 0.01, "--length", 0.03,
            "--curve", "-o", path)
        x, z = read_xz(path)
        ax.fill_between(x * 1e3, z * 1e3, z.min() * 1e3 - 1, color="#c8d7e8")
        ax.plot(x * 1e3, z * 1e3, color="#1f4e79", lw=1)
        ax.set_ylabel(f"K{n}\nz (mm)")
        ax.set_aspect("equal")
        ax.set_ylim(z.min() * 1e3 - 0.5, z.max() * 1e3 + 0.6)
        st = run_json(bin_, "stats", path, "--detrend", "none", "--json")
        smax = st["max_slope_deg"]
        length = float(np.sum(np.hypot(np.diff(x), np.diff(z))))
        lengths.append(length)
        ok_slope &= abs(smax - (n + 1) * alpha) < 1e-6
        f.numbers.append((f"K{n}: points, steepest edge, curve length",
                          f"{len(x)}, {smax:.6f}° (expected {(n + 1) * alpha:g}°), {length * 1e3:.6f} mm"))
    ratio = (2 + 1 / math.cos(math.radians(alpha))) / 3
    for n in range(1, 4):
        ok_len &= abs(lengths[n] / lengths[n - 1] - ratio) < 1e-9
    f.numbers.append(("length ratio K_n / K_(n-1) (expected (2 + 1/cos α)/3 = %.9f)" % ratio,
                      ", ".join(f"{lengths[n] / lengths[n - 1]:.9f}" for n in range(1, 4))))
    axes[-1].set_xlabel("x (mm)")
    fig.suptitle(f"Koch surfaces K0–K3, α = {alpha:g}°, λ = 10 mm (paper Fig. 3)")
    fig.tight_layout()
    f.png = png_bytes(fig)
    f.verdicts.append((ok_slope, "the steepest edge of K_n is (n+1)α", "|max slope − (n+1)α| < 1e-6° for n = 0..3"))
    f.verdicts.append((ok_len, "each iteration multiplies the length by (2 + 1/cos α)/3", "relative error < 1e-9"))
    f.source = f"`frictal surface koch --curve --alpha {alpha:g}` and `frictal stats`"
    return f


def frictal_module(bin_):
    """The frictal Python package of BIN's build (BUILD/python beside BUILD/apps/frictal/frictal), else
    the one installed with it."""
    here = os.path.realpath(os.path.join(os.path.dirname(bin_), "..", "..", "python"))
    if os.path.isdir(os.path.join(here, "frictal")) and here not in sys.path:
        sys.path.insert(0, here)
    import frictal
    return frictal


def world(poly, pose):
    cx, cy, a = pose
    c, s = math.cos(a), math.sin(a)
    return np.column_stack([cx + c * poly[:, 0] - s * poly[:, 1], cy + s * poly[:, 0] + c * poly[:, 1]])


def draw_sphero(ax, pts, r, color):
    """The spheropolygon: the core polygon dilated by r (a band along each edge, a disc at each vertex)."""
    n = len(pts)
    for k in range(n):
        p, q = pts[k], pts[(k + 1) % n]
        d = q - p
        L = math.hypot(*d)
        if L == 0:
            continue
        nrm = np.array([-d[1], d[0]]) / L * r
        ax.add_patch(Polygon([p + nrm, q + nrm, q - nrm, p - nrm], closed=True, color=color, alpha=0.35, lw=0))
        ax.add_patch(Circle(p, r, color=color, alpha=0.35, lw=0))
    ax.add_patch(Polygon(pts, closed=True, fill=False, ec=color, lw=1.2))


def fig05(bin_, work):
    f = Figure(5, "Snapshot of the tilt simulation (spheropolygons)",
               "The blocks are spheropolygons: a polygon core dilated by a small spheroradius r; the lower block is "
               "tilted slowly until the upper one slides, and the tilt angle at the slide is the friction angle "
               "φ = atan μ_a + θ_max (Sec. IV, Fig. 5).")
    frames = f"{work}/k1-frames.txt"
    j = run_json(bin_, "tilt", "koch", "--iterations", 1, "--alpha", 20, "--frames", frames,
                 "--frame-interval", 0.05, "--json")
    fr = frictal_module(bin_).read_tilt_frames(frames)  # the library's reader of its own format
    times = fr["time"]
    slide = j["slide_time_s"] if j.get("slid") else times[-1]
    k = max((i for i in range(len(times)) if times[i] <= slide), key=lambda i: times[i])
    t, tilt = times[k], fr["tilt"][k]
    pose = lambda b: (*fr["position"][k][b], fr["angle"][k][b])  # noqa: E731
    low, up = world(fr["lower_polygon"], pose(0)), world(fr["upper_polygon"], pose(1))
    r = 5e-5
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(7.5, 8.5), gridspec_kw={"height_ratios": [1, 1.3]})
    for pts, col, name in ((low, "#1f77b4", "lower block"), (up, "#d62728", "upper block")):
        a1.add_patch(Polygon(pts, closed=True, color=col, alpha=0.5, label=name))
    allp = np.vstack([low, up])
    a1.set_xlim(allp[:, 0].min() - 0.01, allp[:, 0].max() + 0.01)
    a1.set_ylim(allp[:, 1].min() - 0.01, allp[:, 1].max() + 0.01)
    a1.set_aspect("equal")
    a1.set_xlabel("x (m), world frame")
    a1.set_ylabel("y (m)")
    a1.set_title(f"K1, α = 20°: t = {t:.2f} s, tilt = {math.degrees(tilt):.2f}°")
    a1.legend(loc="upper left", fontsize=8)
    # Zoom on the closest pair of vertices (a contact), with the spheroradius drawn to scale.
    # (away from the blocks' ends: the middle 60 % of the lower block's extent along its length)
    xs = fr["lower_polygon"][:, 0]
    mid = np.abs(xs - 0.5 * (xs.min() + xs.max())) < 0.3 * (xs.max() - xs.min())
    d2 = ((low[:, None, :] - up[None, :, :]) ** 2).sum(-1)
    d2[~mid, :] = np.inf
    i, k = np.unravel_index(np.argmin(d2), d2.shape)
    c = (low[i] + up[k]) / 2
    w = 8 * r
    draw_sphero(a2, low, r, "#1f77b4")
    draw_sphero(a2, up, r, "#d62728")
    a2.set_xlim(c[0] - w, c[0] + w)
    a2.set_ylim(c[1] - w, c[1] + w)
    a2.set_aspect("equal")
    a2.set_title(f"contact, magnified: spheroradius r = {r * 1e6:g} µm", fontsize=10)
    a2.set_xlabel("x (mm)")
    a2.xaxis.set_major_locator(matplotlib.ticker.MaxNLocator(4))
    a2.set_ylabel("y (mm)")
    a2.xaxis.set_major_formatter(matplotlib.ticker.FuncFormatter(lambda v, _: f"{v * 1e3:.2f}"))
    a2.yaxis.set_major_formatter(matplotlib.ticker.FuncFormatter(lambda v, _: f"{v * 1e3:.2f}"))
    a1.add_patch(plt.Rectangle((c[0] - w, c[1] - w), 2 * w, 2 * w, fill=False, ec="k", lw=1))
    fig.tight_layout()
    f.png = png_bytes(fig)
    sim, pred = j["friction_angle_deg"], j["predicted_friction_angle_deg"]
    f.numbers += [("snapshot", f"t = {t:.3f} s, tilt {math.degrees(tilt):.3f}° (last frame before the slide at "
                               f"{slide:.3f} s)"),
                  ("friction angle: simulated / predicted (Eq. 6)", f"{sim:.4f}° / {pred:.4f}°"),
                  ("steps, wall time", f"{j['steps']}, {j['wall_time_s']:.1f} s")]
    f.verdicts.append((bool(j.get("slid")) and abs(sim - pred) < 0.1,
                       "the block slides at the predicted friction angle", "|φ_sim − φ_pred| < 0.1°"))
    f.source = "`frictal tilt koch --iterations 1 --alpha 20 --frames` (format: docs/dem.md)"
    return f


def fig11(bin_, work):
    f = Figure(11, "Deterministic and random Weierstrass–Mandelbrot profiles",
               "The deterministic WM function (Eq. 17, all phases zero) and the randomised one (Eq. 14, random "
               "phases) share every mode's amplitude, hence the same spectrum, while the random phases remove the "
               "regular pattern (Sec. V A, Fig. 11).")
    det, rnd = f"{work}/wm-det.csv", f"{work}/wm-rnd.csv"
    run(bin_, "surface", "wm", "--dimension", 1.5, "--no-stochastic", "-o", det)
    run(bin_, "surface", "wm", "--dimension", 1.5, "--seed", 1, "-o", rnd)
    sd, sr = (run_json(bin_, "stats", det, "--detrend", "none", "--json"),
              run_json(bin_, "stats", rnd, "--detrend", "none", "--json"))
    fig, axes = plt.subplots(2, 1, figsize=(7.5, 4.8), sharex=True)
    for ax, p, name in ((axes[0], det, "deterministic (Eq. 17)"), (axes[1], rnd, "random phases (Eq. 14), seed 1")):
        x, z = read_xz(p)
        ax.plot(x * 1e6, z * 1e9, lw=0.7)
        ax.set_ylabel("z (nm)")
        ax.set_title(name, fontsize=10)
    axes[-1].set_xlabel("x (µm)")
    fig.suptitle("WM profiles, D = 1.5, γ = 1.5, n_max = 10 (paper Fig. 11)")
    fig.tight_layout()
    f.png = png_bytes(fig)
    rel = abs(sd["rms_slope"] - sr["rms_slope"]) / sd["rms_slope"]
    f.numbers += [("rms height: deterministic / random", f"{sd['rms_height_m'] * 1e9:.4f} nm / {sr['rms_height_m'] * 1e9:.4f} nm"),
                  ("rms slope: deterministic / random", f"{sd['rms_slope']:.5f} / {sr['rms_slope']:.5f} (differ by {100 * rel:.2f} %)"),
                  ("steepest edge: deterministic / random", f"{sd['max_slope_deg']:.3f}° / {sr['max_slope_deg']:.3f}°")]
    f.verdicts.append((rel < 0.02, "same mode amplitudes: the same rms slope (a spectral moment)",
                       "rms slopes within 2 %"))
    f.source = "`frictal surface wm --dimension 1.5 [--no-stochastic | --seed 1]`, `frictal stats`"
    return f


def fig12(bin_, work):
    f = Figure(12, "WM profiles for D = 1.0 – 2.0",
               "At fixed rms height, the WM profile gets rougher as the fractal dimension D grows from 1 (smooth, "
               "dominated by the longest wavelength) to 2 (every wavelength with comparable weight) (Fig. 12).")
    ds = [1.0, 1.2, 1.4, 1.6, 1.8, 2.0]
    fig, ax = plt.subplots(figsize=(7.5, 5.5))
    rms_slopes = []
    for k, d in enumerate(ds):
        p = f"{work}/wm-d{d:.1f}.csv"
        run(bin_, "surface", "wm", "--dimension", d, "--seed", 1, "-o", p)
        x, z = read_xz(p)
        off = -6 * k
        ax.plot(x * 1e6, z * 1e9 + off, lw=0.7)
        ax.text(20.3, off, f"D = {d:.1f}", va="center", fontsize=9)
        st = run_json(bin_, "stats", p, "--detrend", "none", "--json")
        rms_slopes.append(st["rms_slope"])
        f.numbers.append((f"D = {d:.1f}: rms height, rms slope, steepest edge",
                          f"{st['rms_height_m'] * 1e9:.3f} nm, {st['rms_slope']:.5f}, {st['max_slope_deg']:.3f}°"))
    ax.set_xlim(0, 23)
    ax.set_yticks([])
    ax.set_xlabel("x (µm)")
    ax.set_ylabel("z (profiles offset by 6 nm)")
    ax.set_title("WM profiles, rms height 1 nm, seed 1 (paper Fig. 12)")
    fig.tight_layout()
    f.png = png_bytes(fig)
    mono = all(b > a for a, b in zip(rms_slopes, rms_slopes[1:]))
    f.verdicts.append((mono, "rougher with D: the rms slope grows with D at equal rms height",
                       "rms slope strictly increasing over D = " + ", ".join(f"{d:.1f}" for d in ds)))
    f.source = "`frictal surface wm --dimension D --seed 1`, `frictal stats`"
    return f


def fig13(bin_, work):
    f = Figure(13, "Linear and cubic-spline interpolation",
               "Between the sample points a profile can be interpolated linearly (slopes jump at every point) or by a "
               "cubic spline (continuous slopes); the paper takes contact slopes from the spline (Sec. V B, Fig. 13). "
               "With the sampling of Eq. 16 (L_s/10) both give the same contact-slope statistics.")
    a, b = f"{work}/wm-pair-1.csv", f"{work}/wm-pair-2.csv"
    run(bin_, "surface", "wm", "--dimension", 1.5, "--seed", 1, "-o", a)
    run(bin_, "surface", "wm", "--dimension", 1.5, "--seed", 2, "-o", b)
    ex = run_json(bin_, "signature", a, b, "--detrend", "none", "--json")
    sp = run_json(bin_, "signature", a, b, "--detrend", "none", "--slopes", "spline", "--json")
    x, z = read_xz(a)
    sel = slice(0, 40)
    xs, zs = x[sel], z[sel]
    # The spline that `--slopes spline` takes, as frictal computes it (`frictal stats --spline`), over
    # the first 400 points (the natural end conditions far from the 40 drawn).
    spl = f"{work}/wm-pair-1-spline.csv"
    h0 = 0.5 * (x[1] - x[0])
    run(bin_, "stats", a, "--detrend", "none", "--crop", f"{x[0] - h0:.17g},{0.5 * (x[399] + x[400]):.17g}", "--spline", spl,
        "--spline-samples", 50)
    d = np.genfromtxt(spl, delimiter=",", names=True)
    keep = d["x_m"] <= xs[-1]
    xf, zf, sf = d["x_m"][keep], d["z_m"][keep], d["slope_deg"][keep]
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(7.5, 5.2), sharex=True)
    a1.plot(xs * 1e9, zs * 1e12, "o", ms=3, color="k", label="samples")
    a1.plot(xs * 1e9, zs * 1e12, "-", lw=1, label="linear")
    a1.plot(xf * 1e9, zf * 1e12, "-", lw=1, label="cubic spline")
    a1.set_ylabel("z (pm)")
    a1.legend(fontsize=8)
    a1.set_title("first 40 points of a WM profile (D = 1.5)", fontsize=10)
    # slopes: linear = piecewise constant; spline = frictal's dz/dx of the cubic
    sl = np.degrees(np.arctan(np.diff(zs) / np.diff(xs)))
    a2.step(xs * 1e9, np.append(sl, sl[-1]), where="post", lw=1, label="linear")
    a2.plot(xf * 1e9, sf, lw=1, label="cubic spline", color="C2")
    a2.set_xlabel("x (nm)")
    a2.set_ylabel("slope (deg)")
    a2.legend(fontsize=8)
    fig.tight_layout()
    f.png = png_bytes(fig)
    ds_ = abs(ex["contact_slope_std_deg"] - sp["contact_slope_std_deg"]) / ex["contact_slope_std_deg"]
    dt = abs(ex["theta_max_forward_deg"] - sp["theta_max_forward_deg"]) / ex["theta_max_forward_deg"]
    f.numbers += [("θ_max forward: exact polyline / spline", f"{ex['theta_max_forward_deg']:.4f}° / {sp['theta_max_forward_deg']:.4f}°"),
                  ("θ_max backward: exact polyline / spline", f"{ex['theta_max_backward_deg']:.4f}° / {sp['theta_max_backward_deg']:.4f}°"),
                  ("σ of contact slopes: exact / spline", f"{ex['contact_slope_std_deg']:.4f}° / {sp['contact_slope_std_deg']:.4f}°")]
    f.verdicts.append((ds_ < 0.02 and dt < 0.1, "linear and spline contact slopes agree at this sampling",
                       f"σ within 2 % ({100 * ds_:.2f} %), θ_max forward within 10 % ({100 * dt:.2f} %)"))
    f.source = ("`frictal signature A B [--slopes spline] --json` on two WM profiles (seeds 1, 2); the spline by "
                "`frictal stats --spline`")
    return f


def fig16(bin_, work, pairs):
    f = Figure(16, "Contact-slope and surface-slope distributions",
               "The distribution of contact slopes θ(x_ofs) is narrower than that of the surface slopes: only a few "
               "of the steepest surface slopes are ever in contact, so θ_max stays below the steepest surface "
               "slope (Sec. V C, Fig. 16).")
    edges = np.linspace(-12, 12, 97)
    surf = np.zeros(len(edges) - 1)
    cont = np.zeros(len(edges) - 1)
    ok_std, ok_max = True, True
    rows = []
    for k in range(pairs):
        a, b = f"{work}/pdf-{k}-a.csv", f"{work}/pdf-{k}-b.csv"
        run(bin_, "surface", "wm", "--dimension", 1.5, "--seed", 2 * k + 1, "-o", a)
        run(bin_, "surface", "wm", "--dimension", 1.5, "--seed", 2 * k + 2, "-o", b)
        pdf = f"{work}/pdf-{k}.csv"
        j = run_json(bin_, "signature", a, b, "--detrend", "none", "--pdf", pdf, "--json")
        s, w = slopes_deg(*read_xz(a))
        s_std = float(np.sqrt(np.average((s - np.average(s, weights=w)) ** 2, weights=w)))
        h, _ = np.histogram(s, bins=edges, weights=w, density=True)
        surf += h / pairs
        with open(pdf) as fh:
            r = list(csv.DictReader(fh))
        lo = np.array([float(x["slope_lo_deg"]) for x in r])
        hi = np.array([float(x["slope_hi_deg"]) for x in r])
        dn = np.array([float(x["density_per_deg"]) for x in r])
        # re-bin the contact PDF onto the common edges (mass per overlap)
        for i in range(len(edges) - 1):
            ov = np.clip(np.minimum(hi, edges[i + 1]) - np.maximum(lo, edges[i]), 0, None)
            cont[i] += float(np.sum(dn * ov)) / (edges[i + 1] - edges[i]) / pairs
        ok_std &= j["contact_slope_std_deg"] < s_std
        tmax = max(j["theta_max_forward_deg"], j["theta_max_backward_deg"])
        ok_max &= tmax < j["surface_slope_max_deg"]
        rows.append((k, j["contact_slope_std_deg"], s_std, tmax, j["surface_slope_max_deg"]))
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.stairs(surf, edges, label="surface slopes", lw=1.5)
    ax.stairs(cont, edges, label="contact slopes θ(x_ofs)", lw=1.5, color="C3")
    ax.set_xlabel("slope (deg)")
    ax.set_ylabel("probability density (1/deg)")
    ax.set_xlim(-6, 6)
    ax.set_title(f"WM pairs, D = 1.5, n_max = 10: mean of {pairs} pairs (paper Fig. 16)")
    ax.legend(fontsize=9)
    fig.tight_layout()
    f.png = png_bytes(fig)
    for k, cs, ss, tm, sm in rows:
        f.numbers.append((f"pair {k + 1}: σ contact / σ surface; max θ / steepest surface edge",
                          f"{cs:.3f}° / {ss:.3f}°; {tm:.3f}° / {sm:.3f}°"))
    f.verdicts.append((ok_std, "the contact-slope distribution is narrower than the surface-slope one",
                       f"σ_contact < σ_surface in every one of {pairs} pairs"))
    f.verdicts.append((ok_max, "θ_max is below the steepest surface slope", f"in every one of {pairs} pairs"))
    f.source = "`frictal signature A B --pdf` on WM pairs (seeds 2k+1, 2k+2)"
    return f


# ---------------------------------------------------------------------------------------------
# Figures from scripts/reproduce's outputs

CLAIMS = {
    4: ("Signature functions of Koch surfaces",
        "The signature function θ(x_ofs) of K_n reaches θ_max = α for K0 and K1, 2α for K2 and 3α for K3 (Sec. III, Fig. 4)."),
    6: ("Friction angle against α", "The friction angle of the spheropolygon simulation follows the signature "
        "prediction φ = θ_max = nα for K0–K3 (Fig. 6)."),
    7: ("Force angle during the tilt", "During the tilt the force angle atan(F_t/F_n) rises to the contact slope "
        "and the block slides when it reaches it (Fig. 7)."),
    8: ("Atomic friction", "The atomic friction angle adds to the signature maximum: φ = atan μ_a + θ_max, the same "
        "for every surface (Eq. 6, Fig. 8)."),
    9: ("Divider dimension of Koch curves", "The divider method recovers the Koch curve's dimension of Eq. 13 "
        "(Sec. IV C 3, Fig. 9)."),
    10: ("Friction coefficient against fractal dimension", "The friction coefficient grows with the fractal "
         "dimension D of the Koch surface (Fig. 10)."),
    14: ("Maximum slopes against resolution", "Maximum contact and surface slopes of WM pairs grow with n_max "
         "(finer wavelengths); the contact slope tends to a finite value for D < 1.5 and keeps growing above (Fig. 14)."),
    15: ("Maximum slopes against D", "The maximum contact slope is smaller than the maximum surface slope; both grow "
         "with D (Sec. V C, Fig. 15)."),
    17: ("Slope standard deviations against resolution", "The standard deviations of contact and surface slopes grow "
         "with D, increasingly fast above D ≈ 1.5 (Fig. 17)."),
    18: ("Slope standard deviations against D", "The standard deviations of contact and surface slopes grow with D "
         "(Fig. 18)."),
}

# Results beyond the paper, drawn from a study's exported tables like the paper's figures: key -> (title,
# question, study name, the claims of the catalogue (`frictal study report --json`) it shows; the PNG
# is OUTDIR/<key>.png).
BEYOND = {
    "wm-tilt": ("Tilt test on random pairs",
                "Not in the paper, which simulates Koch surfaces only: the spheropolygon tilt test on stochastic WM pairs "
                "and on Fourier-filtered self-affine pairs scaled to the Table I block, 20 pairs per D. Eq. 18 claims φ − θ_a lies in [θ_max − σ, θ_max]; the "
                "report states how often it does, whether the angle depends on the run-away distance (0.5, 1, 2 λ), "
                "and whether the rigid or the spheropolygon prediction is closer (docs/dem.md sec. 6).",
                "wm-tilt", ("eq18-range", "runaway-independent", "sphero-closer-than-rigid")),
    "eq18-derived": ("Eq. 18 derived: the hold angle over drops",
                     "Eq. 18 is a heuristic: φ − θ_a in [θ_max − σ, θ_max]. What repeated tilt tests of one pair give "
                     "can be derived instead: a block dropped at a random offset rests in a basin of the lift h and "
                     "holds until the quasi-static hold angle φ_qs of that basin (docs/analysis.md). Per D, the "
                     "distribution of φ_qs over drops (mean, 5–95 %) beside Eq. 18's range and the inertial bound "
                     "φ_in; and the quasi-static tilt test against φ_qs from where its block rests (docs/dem.md sec. 6).",
                     "wm-tilt", ("eq18-over-drops", "dynamic-hold-bracket", "quasi-static-hold")),
    "areal-tilt": ("3D tilt test of areal blocks (MuJoCo)",
                   "Not in the paper, whose theory is one-dimensional: two maps as rigid blocks, the upper one free "
                   "to move sideways as real blocks do (or locked to the sliding direction), tilted quasi-statically "
                   "on MuJoCo (a sphere on each node of the upper map over the lower map's height field) against the "
                   "hold angle that the lift over two dimensions of offset predicts for the same spheres and "
                   "triangles (docs/mujoco.md). The grey bars are the prediction's spread: the hold angles "
                   "the rigid block reaches when one slip's end is moved by a sphere radius, wide where a drop's "
                   "hold angle hinges on where a slip ends.",
                   "areal-tilt", ("areal-matched-prediction", "areal-prediction-spread", "areal-seat-by-seat")),
}


def label(f):
    return f"Fig. {f.number}" if isinstance(f.number, int) else "Beyond the paper"


# ---------------------------------------------------------------------------------------------
# The findings as data: `frictal study report --json` over every store (scripts/reproduce writes
# OUTDIR/studies/findings.json): one conclusion per claim, and the per-part findings behind it.

class Findings:
    def __init__(self, data):
        self.conclusions = list(data.get("conclusions", []))
        self.by_id = {c["id"]: c for c in self.conclusions}
        self.catalogue = {c["id"]: c for c in data.get("claims", [])}
        # (claim id, study, part) -> the finding (criterion, numbers, cause)
        self.detail = {}
        for r in data.get("reports", []):
            for f in r["findings"]:
                self.detail[(f["claim_id"], r["study"], f["part"])] = f

    @staticmethod
    def load(out, bin_):
        path = f"{out}/studies/findings.json"
        if not os.path.exists(path):  # the stores alone: ask the CLI
            stores = sorted(p for p in glob.glob(f"{out}/studies/*.sqlite")
                            if os.path.basename(p) != "results-cache.sqlite")  # the cache is no study
            if not stores:
                return Findings({})
            run(bin_, "study", "report", "--json", *stores, "-o", path)
        with open(path, encoding="utf-8") as fh:
            return Findings(json.load(fh))

    def add_check(self, cid, statement, where, figures, supported, criterion):
        """A paper claim checked here (a figure computed by this script): into the conclusion of the
        same claim when the studies check it too (e.g. Fig. 4's maxima), else a conclusion of its own."""
        c = self.by_id.get(cid)
        if c is None:
            c = {"id": cid, "source": "paper", "statement": statement, "where": where, "figures": figures,
                 "verdict": "supported", "cause": "", "uncaused": [], "checks": [], "superseded_by": []}
            self.by_id[cid] = c
            self.conclusions.append(c)
        c["checks"].append({"study": "index", "part": f"Fig. {figures[0]}", "verdict":
                            "supported" if supported else "not supported", "cause": "", "criterion": criterion})
        if not supported:
            c["verdict"] = "not supported"
            c["uncaused"].append(f"index/Fig. {figures[0]}")

    def for_figure(self, n):
        return [c for c in self.conclusions if n in c.get("figures", [])]


def checks_of(c, findings, studies=None):
    """(study, part, verdict, criterion, cause) of a conclusion's checks; those of `studies` when
    any of them is, else all."""
    rows = []
    for ch in c["checks"]:
        f = findings.detail.get((c["id"], ch["study"], ch["part"]), {})
        rows.append((ch["study"], ch["part"], ch["verdict"], ch.get("criterion") or f.get("criterion", ""),
                     ch.get("cause") or f.get("cause", "")))
    if studies:
        mine = [r for r in rows if r[0] in studies]
        if mine:
            return mine
    return rows


def figure_studies(out, n):
    """The studies named after figure n ("fig06-...", "fig14-18-...")."""
    names = set()
    for path in glob.glob(f"{out}/studies/*.sqlite"):
        study = os.path.basename(path)[: -len(".sqlite")]
        m = re.match(r"fig(\d+)(?:-(\d+))?-", study)
        if m and int(m.group(1)) <= n <= int(m.group(2) or m.group(1)):
            names.add(study)
    return names


def fig04_from(out):
    f = Figure(4, *CLAIMS[4])
    png = f"{out}/fig04/fig04.png"
    summary = f"{out}/fig04/maxima.csv"
    if not os.path.exists(png):
        f.missing = f"{png} not found (scripts/reproduce draws it)"
        return f
    f.png = open(png, "rb").read()
    for n in range(4):
        jp = f"{out}/fig04/k{n}.json"
        if os.path.exists(jp):
            j = json.load(open(jp))
            f.numbers.append((f"K{n}, α = 5°: θ_max forward / backward",
                              f"{j['theta_max_forward_deg']:.9f}° / {j['theta_max_backward_deg']:.9f}°"))
    if not os.path.exists(summary):  # the per-surface JSONs alone: theta_max = n alpha at alpha = 5 deg
        ok, have = True, 0
        for n, mult in enumerate([1, 1, 2, 3]):
            jp = f"{out}/fig04/k{n}.json"
            if os.path.exists(jp):
                j = json.load(open(jp))
                have += 1
                ok &= all(abs(j[k] - 5.0 * mult) < 1e-6 for k in ("theta_max_forward_deg", "theta_max_backward_deg"))
        if have:
            f.verdicts.append((ok and have == 4, "θ_max = nα (n = 1, 1, 2, 3) at α = 5°",
                               f"|θ_max − nα| < 1e-6° in both directions for {have} of 4 surfaces", "koch-theta-max"))
    if os.path.exists(summary):
        rows = list(csv.DictReader(open(summary)))
        agree = sum(r["agrees"] == "yes" for r in rows)
        f.numbers.append(("Koch surfaces of Table I whose θ_max = nα (both directions)", f"{agree} of {len(rows)}"))
        f.verdicts.append((agree == len(rows) and len(rows) > 0, "θ_max = nα (n = 1, 1, 2, 3) for every α of Table I",
                           f"|θ_max − nα| < 1e-6° in both directions, {agree} of {len(rows)} Koch surfaces of Table I",
                           "koch-theta-max"))
    f.source = "scripts/reproduce: `frictal signature --period 0.01` on K0–K3"
    return f


def store_rows(out, study, f, how):
    """(part, scalars) of every done task of a study, from the tables `frictal study export --csv`
    wrote (OUT/studies/STUDY/PART.csv: parameters then scalars; empty = NaN, read as None); None
    (and f.missing set, saying `how` they are made) when there are none."""
    f.missing = None
    parts = [p for p in sorted(glob.glob(f"{out}/studies/{study}/*.csv"))
             if not p.endswith(("-arrays.csv", "-pooled-pdfs.csv")) and os.path.basename(p) != "tasks.csv"]
    if not parts:
        f.missing = f"{out}/studies/{study}/PART.csv not found ({how}; `frictal study export --csv` writes them)"
        return None

    def value(v):
        if v == "":
            return None
        try:
            return float(v)
        except ValueError:
            return v

    rows = []
    for path in parts:
        part = os.path.basename(path)[: -len(".csv")]
        with open(path, newline="", encoding="utf-8") as fh:
            rows += [(part, {k: value(v) for k, v in r.items()}) for r in csv.DictReader(fh)]
    return rows


def eq18_derived(out):
    """The hold angle over drops against Eq. 18, per D, from the wm-tilt store."""
    f = study_figure(out, "eq18-derived")
    rows = store_rows(out, "wm-tilt", f, "scripts/reproduce runs the wm-tilt study")
    if rows is None:
        return f
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    plt.rcParams.update({"font.size": 12})  # the page shows it 560 px wide
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.6), sharey=False)
    drew = False
    for ax, part, name in ((axes[0], "wm", "Weierstrass–Mandelbrot pairs"), (axes[1], "fourier", "Fourier-filtered pairs")):
        by = {}
        for p, s in rows:
            if p != part or s.get("hold_mean_deg") is None:
                continue
            by.setdefault(round(s["surface_dimension"], 6), []).append(s)
        if not by:
            continue
        D = sorted(by)
        mean = lambda k: [sum(r[k] for r in by[d] if r.get(k) is not None) / max(1, sum(r.get(k) is not None for r in by[d])) for d in D]  # noqa: E731
        lo, hi = mean("eq18_low_deg"), mean("eq18_high_deg")
        ax.fill_between(D, lo, hi, color="#f2c94c", alpha=0.35, label="Eq. 18: [θ_max − σ, θ_max] + θ_a")
        m, q05, q95 = mean("hold_mean_deg"), mean("hold_q05_deg"), mean("hold_q95_deg")
        ax.errorbar(D, m, yerr=[[a - b for a, b in zip(m, q05)], [b - a for a, b in zip(m, q95)]], fmt="o-",
                    color="C0", capsize=3, label="φ_qs over drops: mean, 5–95 %")
        ax.plot(D, mean("inertial_hold_mean_deg"), "v--", color="C4", label="φ_in over drops: mean")
        ax.plot(D, mean("friction_angle_deg"), "s", color="k", mfc="none", label="constant-rate tilt (Table II k_n): mean")
        ax.set_xlabel("fractal dimension D" + (" (= 2 − H)" if part == "fourier" else ""))
        ax.set_ylabel("friction angle φ (deg)")
        ax.set_title(name, fontsize=10)
        ax.grid(alpha=0.3)
        drew = True
        for d in D:
            r = by[d]
            avg = lambda k: sum(x[k] for x in r) / len(r)  # noqa: E731
            f.numbers.append((f"{part}, D = {d:.1f}: Eq. 18 range / φ_qs over drops (mean, 5–95 %) / φ_in mean",
                              f"{avg('eq18_low_deg'):.3f}–{avg('eq18_high_deg'):.3f}° / {avg('hold_mean_deg'):.3f}° "
                              f"({avg('hold_q05_deg'):.3f}–{avg('hold_q95_deg'):.3f}°) / {avg('inertial_hold_mean_deg'):.3f}°"))
    for part in ("wm-quasi-static", "fourier-quasi-static", "wm-quasi-static-table2"):
        r = [s for p, s in rows if p == part and s.get("sphero_hold_angle_deg") is not None]
        if not r:
            continue
        d1 = [s["friction_minus_sphero_hold_deg"] for s in r if s.get("friction_minus_sphero_hold_deg") is not None]
        d2 = [s["stiff_minus_sphero_hold_deg"] for s in r if s.get("stiff_minus_sphero_hold_deg") is not None]
        txt = f"mean φ − φ_qs {sum(d1) / len(d1):+.3f}° (|.| ≤ 0.1° in {sum(abs(x) <= 0.1 for x in d1)} of {len(d1)})" if d1 else "-"
        if d2:
            txt += f"; at 10 k_n {sum(d2) / len(d2):+.3f}° ({sum(abs(x) <= 0.1 for x in d2)} of {len(d2)} within 0.1°)"
        f.numbers.append((f"quasi-static tilt, part {part}", txt))
    if not drew:
        f.missing = "no wm-tilt task with the hold angle in the store (kind version >= 3)"
        plt.close(fig)
        return f
    axes[0].legend(fontsize=9, loc="upper left")
    fig.tight_layout()
    png = f"{out}/eq18-derived.png"
    fig.savefig(png, dpi=110)
    plt.close(fig)
    f.png = open(png, "rb").read()
    f.source = "the wm-tilt store (frictal study run studies/wm-tilt.toml), drawn by scripts/make_index.py"
    return f


def areal_tilt_figure(out):
    """The 3D tilt test against its matched prediction, free and locked, from the areal-tilt store."""
    f = study_figure(out, "areal-tilt")
    rows = store_rows(out, "areal-tilt", f, "scripts/reproduce runs the areal-tilt study when the build has MuJoCo")
    if rows is None:
        return f
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rows = [(p, s) for p, s in rows if s.get("simulated_free_deg") is not None]
    if not rows:
        f.missing = "no finished areal-tilt task in the store"
        return f
    plt.rcParams.update({"font.size": 12})
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.8))
    top = max(max(s["matched_free_deg"], s["simulated_free_deg"], s["matched_locked_deg"], s["simulated_locked_deg"])
              for _, s in rows) * 1.08 + 0.5
    for ax, mode, name in ((axes[0], "free", "free to move sideways"), (axes[1], "locked", "locked to the direction d")):
        ax.fill_between([0, top], [-0.2, top - 0.2], [0.2, top + 0.2], color="#9ecae1", alpha=0.5,
                        label="within 0.2° of the prediction")
        ax.plot([0, top], [0, top], color="#3182bd", lw=1)
        # The prediction's spread (one slip's end moved by a sphere radius): a bar along x.
        spread = [(s[f"spread_low_{mode}_deg"], s[f"spread_high_{mode}_deg"], s[f"simulated_{mode}_deg"])
                  for _, s in rows if isinstance(s.get(f"spread_low_{mode}_deg"), (int, float))]
        if spread:
            ax.hlines([y for _, _, y in spread], [lo for lo, _, _ in spread], [hi for _, hi, _ in spread],
                      color="0.45", lw=1.2, label="spread: a slip's end moved by r")
        for part, marker, color in (("grooves", "o", "C1"), ("fourier", "s", "C2")):
            pts = [(s[f"matched_{mode}_deg"], s[f"simulated_{mode}_deg"], s[f"within_{mode}"] > 0.5)
                   for p, s in rows if p == part]
            if not pts:
                continue
            ax.plot([a for a, b, ok in pts if ok], [b for a, b, ok in pts if ok], marker, color=color, mfc="none",
                    label=f"{part}: agrees")
            miss = [(a, b) for a, b, ok in pts if not ok]
            if miss:
                ax.plot([a for a, b in miss], [b for a, b in miss], marker, color="#b00020",
                        label=f"{part}: misses (> 0.2°)")
        ax.set_xlim(0, top)
        ax.set_ylim(0, top)
        ax.set_xlabel("predicted hold angle, matched spheres and triangles (deg)")
        ax.set_ylabel("MuJoCo tilt test: friction angle (deg)")
        ax.set_title(f"block {name}", fontsize=11)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=9, loc="upper left")
    fig.tight_layout()
    png = f"{out}/areal-tilt.png"
    fig.savefig(png, dpi=110)
    plt.close(fig)
    f.png = open(png, "rb").read()
    n = len(rows)
    for mode in ("free", "locked"):
        ok = sum(s[f"within_{mode}"] > 0.5 for _, s in rows)
        worst = max(s[f"miss_{mode}_deg"] for _, s in rows)
        f.numbers.append((f"{mode}: within 0.2° of the matched prediction", f"{ok} of {n} pairs (largest miss {worst:.3f}°)"))
    spread = [s[f"within_spread_{m}"] > 0.5 for _, s in rows for m in ("free", "locked")
              if isinstance(s.get(f"within_spread_{m}"), (int, float))]
    if spread:
        wide = sum(s[f"spread_high_{m}_deg"] - s[f"spread_low_{m}_deg"] > 0.2 for _, s in rows for m in ("free", "locked")
                   if isinstance(s.get(f"spread_low_{m}_deg"), (int, float)))
        f.numbers.append(("within 0.2° of the prediction's spread (one slip's end moved by a sphere radius)",
                          f"{sum(spread)} of {len(spread)} runs; the spread is wider than 0.2° in {wide}"))
    seated = [(s[f"simulated_{m}_deg"], s[f"seated_{m}_deg"]) for _, s in rows for m in ("free", "locked")
              if isinstance(s.get(f"seated_{m}_deg"), float) and math.isfinite(s[f"seated_{m}_deg"])]
    if seated:
        miss = [b - a if b > a else max(0.0, a - 0.1 - b) for a, b in seated]
        f.numbers.append(("from the simulated block's last seat: the rigid block within 0.2°",
                          f"{sum(x <= 0.2 for x in miss)} of {len(miss)} runs (largest miss {max(miss):.3f}°)"))
    steer = [abs(s["steering_deg"]) for _, s in rows if s.get("steering_deg") is not None]
    if steer:
        f.numbers.append(("steering: angle between d and the free block's path", f"mean {sum(steer) / len(steer):.1f}°, "
                          f"largest {max(steer):.1f}°"))
    f.source = "the areal-tilt store (frictal study run studies/areal-tilt.toml), drawn by scripts/make_index.py"
    return f


def study_figure(out, n):
    title, claim = CLAIMS[n] if isinstance(n, int) else BEYOND[n][:2]
    f = Figure(n, title, claim)
    png = f"{out}/fig{n:02d}.png" if isinstance(n, int) else f"{out}/{n}.png"
    if os.path.exists(png):
        f.png = open(png, "rb").read()
    else:
        f.missing = f"{png} not found (scripts/plot_studies.py draws it from the study stores)"
    f.source = "the study stores under studies/ (frictal study run/report), plotted by scripts/plot_studies.py"
    return f


# ---------------------------------------------------------------------------------------------
# The page

STYLE = """
body { font-family: "DejaVu Sans", Arial, sans-serif; max-width: 1200px; margin: 1.5em auto; padding: 0 1em; color: #222; line-height: 1.4; }
h1 { font-size: 1.5em; } h2 { font-size: 1.15em; margin: 0 0 .4em 0; }
.fig { display: flex; gap: 1.5em; border-top: 1px solid #ccc; padding: 1.2em 0; align-items: flex-start; }
.fig .img { flex: 0 0 560px; } .fig img { width: 560px; height: auto; border: 1px solid #eee; }
.fig .text { flex: 1; min-width: 0; }
.claim { font-style: italic; color: #333; }
table { border-collapse: collapse; font-size: .88em; margin: .5em 0; } th, td { border: 1px solid #ddd; padding: .2em .5em; text-align: left; vertical-align: top; }
.ok { color: #1e7b1e; font-weight: bold; } .no { color: #b00020; font-weight: bold; }
.missing { color: #8a6d00; background: #fff8e1; padding: .6em; }
.summary { background: #f3f7ee; border-left: 4px solid #5a9a2a; padding: .5em .8em; }
.sup { color: #5b3a9e; font-weight: bold; } .suptext { color: #5b3a9e; font-size: .9em; }
.conclusions ol li { margin: .45em 0; } .verdicts li { margin: .3em 0; } details { font-size: .9em; }
.crit { color: #555; font-size: .88em; } .cause { color: #6a4a00; font-size: .88em; }
.nocause { color: #a00; font-size: .88em; font-weight: bold; } .src { color: #666; font-size: .85em; }
"""


VERDICT = {"supported": ("ok", "SUPPORTED"), "not supported": ("no", "NOT SUPPORTED"),
           "superseded": ("sup", "SUPERSEDED")}


def badge(verdict):
    cls, word = VERDICT.get(verdict, ("no", verdict.upper()))
    return f"<span class=\"{cls}\">{word}</span>"


def where_html(c, anchors):
    """The claim's place in the paper, with links to the figures on this page."""
    links = [f"<a href=\"#fig{n}\">Fig. {n}</a>" for n in c.get("figures", []) if f"fig{n}" in anchors]
    return html.escape(c.get("where", "")) + (f" (on this page: {', '.join(links)})" if links else "")


def conclusion_html(c, findings, anchors):
    """One claim: its verdict and why (the measured cause, or the finding that supersedes it)."""
    n = len(c["checks"])
    good = sum(ch["verdict"] == "supported" for ch in c["checks"])
    parts = [f"<li id=\"claim-{html.escape(c['id'])}\">{badge(c['verdict'])} {html.escape(c['statement'])}"
             f"<br><span class=\"crit\">{where_html(c, anchors)}; checked on {n} part{'s' * (n != 1)}"
             + (f", supported on {good}" if good != n else "") + "</span>"]
    if c["verdict"] == "superseded":
        subs = [findings.by_id[i] for i in c.get("superseded_by", []) if i in findings.by_id]
        parts.append("<br><span class=\"suptext\">superseded by frictal's own finding: "
                     + "; ".join(f"<a href=\"#claim-{html.escape(x['id'])}\">{html.escape(x['statement'])}</a>"
                                 for x in subs) + "</span>")
    if c["verdict"] != "supported":
        if c.get("cause"):
            parts.append(f"<br><span class=\"cause\">measured cause: {html.escape(c['cause'])}</span>")
        if c.get("uncaused"):
            parts.append("<br><span class=\"nocause\">no cause measured on "
                         + html.escape(", ".join(c["uncaused"])) + "</span>")
    parts.append("</li>")
    return "".join(parts)


def figure_verdict_html(c, findings, studies):
    """A claim on a figure: the verdict over all parts, and the parts of this figure's studies."""
    rows = checks_of(c, findings, studies)
    items = "".join(
        f"<li>{badge(v)} {html.escape(st)}/{html.escape(pt)}"
        + (f"<br><span class=\"crit\">criterion: {html.escape(cr)}</span>" if cr else "")
        + (f"<br><span class=\"cause\">cause: {html.escape(ca)}</span>" if ca and v != "supported" else "") + "</li>"
        for st, pt, v, cr, ca in rows)
    return (f"<li>{badge(c['verdict'])} <a href=\"#claim-{html.escape(c['id'])}\">{html.escape(c['statement'])}</a>"
            f"<details><summary>checked on {len(rows)} part{'s' * (len(rows) != 1)}"
            + (" of this figure's studies" if studies and any(r[0] in studies for r in rows) else "")
            + f"</summary><ul>{items}</ul></details></li>")


def render(figs, findings, title, note):
    anchors = {f"fig{f.number}" for f in figs}
    # the paper's claims in the order of their first figure (those without one after)
    paper = sorted((c for c in findings.conclusions if c.get("source") == "paper"),
                   key=lambda c: min(c.get("figures") or [99]))
    own = [c for c in findings.conclusions if c.get("source") != "paper"]
    count = lambda cs, v: sum(c["verdict"] == v for c in cs)  # noqa: E731
    drawn = sum(f.png is not None for f in figs)
    parts = ["<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n",
             f"<title>{html.escape(title)}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n",
             f"<h1>{html.escape(title)}</h1>\n",
             "<p>F. Alonso-Marroquín, P. Huang, D. A. H. Hanaor, E. A. Flores-Johnson, G. Proust, Y. Gan and L. Shen, "
             "“Static friction between rigid fractal surfaces”, Phys. Rev. E 92, 032405 (2015). One verdict per claim "
             "of the paper that frictal checks, over every study part that checks it (supported; not supported, "
             "with the cause the data measure; or superseded by frictal's own finding), then frictal's own findings, "
             f"then each figure with its numbers. {html.escape(note)}</p>\n",
             f"<p class=\"summary\">The paper's claims: <b>{count(paper, 'supported')} of {len(paper)} supported</b>"
             f", {count(paper, 'superseded')} superseded by frictal's own findings, "
             f"{count(paper, 'not supported')} not supported. frictal's own findings: "
             f"<b>{count(own, 'supported')} of {len(own)} supported</b>"
             + (f", {len(own) - count(own, 'supported')} not supported" if len(own) > count(own, "supported") else "")
             + f". {drawn} of {len(figs)} figures drawn.</p>\n<nav>"]
    parts += [f"<a href=\"#fig{f.number}\">{html.escape(label(f) if isinstance(f.number, int) else f.number)}</a> "
              for f in figs]
    parts.append("</nav>\n<section class=\"conclusions\">\n<h2>The paper's claims</h2>\n<ol>")
    parts += [conclusion_html(c, findings, anchors) for c in paper]
    parts.append("</ol>\n<h2>frictal's own findings</h2>\n<p class=\"crit\">What frictal found where the paper's "
                 "claim does not hold, and questions the paper does not ask (the docs section that explains each).</p>\n<ol>")
    parts += [conclusion_html(c, findings, anchors) for c in own]
    parts.append("</ol>\n</section>\n")
    for f in figs:
        parts.append(f"<section class=\"fig\" id=\"fig{f.number}\">\n<div class=\"img\">")
        if f.png is not None:
            b64 = base64.b64encode(f.png).decode()
            parts.append(f"<img alt=\"{label(f)}: {html.escape(f.title)}\" src=\"data:image/png;base64,{b64}\">")
        else:
            parts.append(f"<p class=\"missing\">Not produced in this run: {html.escape(f.missing or 'no figure')}</p>")
        parts.append("</div>\n<div class=\"text\">")
        parts.append(f"<h2>{label(f)}: {html.escape(f.title)}</h2>")
        parts.append(f"<p class=\"claim\">{'Paper' if isinstance(f.number, int) else 'Question'}: "
                     f"{html.escape(f.claim)}</p>")
        if f.numbers:
            parts.append("<table>" + "".join(f"<tr><th>{html.escape(a)}</th><td>{html.escape(b)}</td></tr>"
                                             for a, b in f.numbers) + "</table>")
        if f.conclusions:
            parts.append("<ul class=\"verdicts\">")
            parts += [figure_verdict_html(c, findings, f.studies) for c in f.conclusions]
            parts.append("</ul>")
        elif f.png is not None:
            parts.append("<p class=\"crit\">No claim checked in this run speaks to this figure.</p>")
        if f.source:
            parts.append(f"<p class=\"src\">Computed by {html.escape(f.source)}.</p>")
        parts.append("</div>\n</section>\n")
    parts.append("</body>\n</html>\n")
    return "".join(parts)


def slug(text):
    return re.sub(r"[^a-z0-9]+", "-", text.lower()).strip("-")[:48]


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("bin", help="the frictal executable")
    ap.add_argument("out", help="the output folder of scripts/reproduce")
    ap.add_argument("--quick", action="store_true", help="fewer WM pairs for Fig. 16")
    ap.add_argument("--only", default="", help="comma-separated figure numbers (or wm-tilt) to compute (default: all)")
    a = ap.parse_args(argv)
    work = f"{a.out}/index"
    os.makedirs(work, exist_ok=True)
    only = {int(x) if x.strip().isdigit() else x.strip() for x in a.only.split(",") if x.strip()}
    want = lambda n: not only or n in only  # noqa: E731
    findings = Findings.load(a.out, a.bin)
    computed = {3: lambda: fig03(a.bin, work), 5: lambda: fig05(a.bin, work), 11: lambda: fig11(a.bin, work),
                12: lambda: fig12(a.bin, work), 13: lambda: fig13(a.bin, work),
                16: lambda: fig16(a.bin, work, 3 if a.quick else 10)}
    figs = []
    for n in [3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18]:
        if not want(n):
            continue
        if n in computed:
            try:
                f = computed[n]()
            except Exception as e:  # reported on the page and on stderr, never silently
                print(f"make_index: Fig. {n}: {e}", file=sys.stderr)
                f = Figure(n, f"Fig. {n}", "")
                f.missing = f"computing it failed: {e}"
            if f.png is not None:
                with open(f"{work}/fig{n:02d}.png", "wb") as fh:
                    fh.write(f.png)
        elif n == 4:
            f = fig04_from(a.out)
        else:
            f = study_figure(a.out, n)
        # The claims this script checks on the figures it computes: conclusions beside the studies'.
        for v in f.verdicts:
            ok, text, crit = v[:3]
            findings.add_check(v[3] if len(v) > 3 else f"fig{n:02d}-{slug(text)}", (text[:1].upper() if text[:1].isascii() else text[:1]) + text[1:] + ".",
                               f"Fig. {n}", [n], ok, crit)
        figs.append(f)
    for key in BEYOND:
        if want(key):
            if key == "eq18-derived":
                figs.append(eq18_derived(a.out))
            elif key == "areal-tilt":
                figs.append(areal_tilt_figure(a.out))
            else:
                figs.append(study_figure(a.out, key))
    for f in figs:
        if isinstance(f.number, int):
            f.conclusions, f.studies = findings.for_figure(f.number), figure_studies(a.out, f.number)
        else:
            f.conclusions = [findings.by_id[i] for i in BEYOND[f.number][3] if i in findings.by_id]
            f.studies = {BEYOND[f.number][2]}
    note = "Quick scale (QUICK=1): small grids." if a.quick else "Full scale."
    page = render(figs, findings, "frictal: the paper's claims and figures, reproduced", note)
    with open(f"{a.out}/index.html", "w", encoding="utf-8") as fh:
        fh.write(page)
    bad = [f.number for f in figs if f.missing]
    paper = [c for c in findings.conclusions if c.get("source") == "paper"]
    print(f"make_index: wrote {a.out}/index.html ({len(figs)} figures; the paper's claims: "
          + ", ".join(f"{sum(c['verdict'] == v for c in paper)} {v}" for v in VERDICT)
          + (f"; not produced: {', '.join(f'Fig. {n}' for n in bad)}" if bad else "") + ")")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
