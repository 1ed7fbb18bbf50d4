#!/usr/bin/env python3
"""Rough contact: the relative contact area against load of `frictal contact` on generated
self-affine maps, as kappa = (A / A0) / (p / (E* g)), g the rms gradient of the surface
(sqrt(<|grad h|^2>), from its spectrum).

At small loads the area grows linearly with the load: kappa = sqrt(8 / pi) = 1.60 in Persson's
theory, sqrt(2 pi) = 2.51 in Bush, Gibson and Thomas's, and about 2 in boundary-element and
Green's-function simulations (Hyun, Pei, Molinari & Robbins, Phys. Rev. E 2004; Prodanov, Dapp &
Muser, Tribol. Lett. 2014; Yastrebov, Anciaux & Molinari, J. Mech. Phys. Solids 2017, whose fit
makes kappa fall slowly, logarithmically, with the Nayak parameter, i.e. with the spectrum's
breadth). The maps: periodic, n x n, Hurst 0.8, spectrum flat from the longest wavelength L to the
roll-off L / 4 and C(q) ~ q^-(2 + 2H) from there to the short cutoff at 16 spacings (each contact
spot resolved by several points), random phases; E* = 1 GPa; loads p / (E* g) from 0.005 to 0.05
(1-10 % contact), one load curve per map (warm starts).

The mean separation u (the mean gap, the periodic convention: the flat's distance from the
surface's mean plane) is compared with Persson's theory (Yang & Persson, J. Phys.: Condens.
Matter 20, 215214, 2008; Persson, Phys. Rev. Lett. 99, 125502, 2007):
u(p) = sqrt(pi) int dq q^2 C(q) w(q) int_p^inf dp'/p' [gamma + 3 (1 - gamma) P(q, p')^2]
exp(-(w(q) p' / E*)^2), w(q) = (pi int_q0^q dq' q'^3 C(q'))^(-1/2), P(q, p) = erf(w(q) p / E*),
gamma = 0.45, with the surface's own spectrum C(q) (2 pi int q C dq = the mean square height).

The area counted as the points that carry pressure overestimates the true area at a finite
resolution, by about the contact's perimeter times a fraction of the spacing. The corrected area
of Yastrebov, Anciaux & Molinari (Tribol. Int. 114, 2017, Eq. 15, "On the accurate computation of
the true contact-area in mechanical contact of random rough surfaces"):
A* / A0 = N_a / N^2 - (pi - 1 + ln 2) / 24 M / N^2, N_a the points in contact and M the changes
between contact and no contact along the grid's rows and columns (periodic: across the edge too).

Usage: PYTHONPATH=build/release/python python3 bench/contact_rough.py [N] [SEEDS] [OUT.md]"""
import datetime
import math
import platform
import sys
import time

import numpy as np
from scipy.special import erf

import frictal


def surface(n, dx, seed, hurst=0.8, rolloff_cells=None, cutoff_cells=16):
    rng = np.random.default_rng(seed)
    L = n * dx
    q = 2 * np.pi * np.hypot(*np.meshgrid(np.fft.fftfreq(n, dx), np.fft.fftfreq(n, dx)))
    qr = 2 * np.pi / (L / 4) if rolloff_cells is None else 2 * np.pi / (rolloff_cells * dx)
    qs = 2 * np.pi / (cutoff_cells * dx)
    C = np.where((q > 0) & (q <= qs), np.maximum(q, qr) ** (-2 - 2 * hurst), 0.0)
    hq = np.sqrt(C) * np.exp(2j * np.pi * rng.random((n, n)))
    h = np.fft.ifft2(hq).real
    # rms gradient from the spectrum of h itself (exact for the periodic band-limited surface)
    Hq = np.fft.fft2(h)
    g = math.sqrt(float(np.sum(q ** 2 * np.abs(Hq) ** 2)) / n ** 4)
    m0 = math.sqrt(float(np.mean(h ** 2)))
    m2 = g ** 2 / 2
    m4 = float(np.sum(q ** 4 * np.abs(Hq) ** 2)) / n ** 4 * 3 / 8
    nayak = m0 ** 2 * m4 / m2 ** 2  # alpha = m0 m4 / m2^2 (isotropic), m0 the variance
    return h, g, nayak


def corrected_area(pressure):
    """The area fraction with the perimeter correction (module docstring) of a periodic pressure
    field: (N_a - (pi - 1 + ln 2) / 24 M) / N^2."""
    c = np.asarray(pressure) > 0
    switches = int(np.count_nonzero(c != np.roll(c, 1, axis=0)) + np.count_nonzero(c != np.roll(c, 1, axis=1)))
    return (np.count_nonzero(c) - (math.pi - 1 + math.log(2)) / 24 * switches) / c.size


def persson_separation(h, dx, pressures, Es, gamma=0.45):
    """Persson's mean separation (m) at the nominal pressures (Pa) for the periodic surface h (m)
    on spacing dx (m): the sums over the surface's Fourier modes stand for the isotropic
    integrals, int d^2q f(q) = 2 pi int q f(q) dq, with C(q) = |H(q)|^2 / n^4 (L / 2 pi)^2."""
    n = h.shape[0]
    L = n * dx
    q = 2 * np.pi * np.hypot(*np.meshgrid(np.fft.fftfreq(n, dx), np.fft.fftfreq(n, dx))).ravel()
    C = (np.abs(np.fft.fft2(h)).ravel() ** 2 / n ** 4) * (L / (2 * np.pi)) ** 2
    keep = q > 0
    q, C = q[keep], C[keep]
    order = np.argsort(q)
    q, C = q[order], C[order]
    dq2 = (2 * np.pi / L) ** 2  # the area of one mode in q space
    # int_q0^q dq' q'^3 C = (1 / 2 pi) sum over the modes up to q of q^2 C dq2
    cum = np.cumsum(q ** 2 * C * dq2) / (2 * np.pi)
    w = 1 / np.sqrt(np.pi * cum)
    # F(x0) = int_x0^inf dx / x [gamma + 3 (1 - gamma) erf(x)^2] exp(-x^2), on a log grid
    xs = np.logspace(-9, 1.5, 4000)
    f = (gamma + 3 * (1 - gamma) * erf(xs) ** 2) * np.exp(-xs ** 2)  # integrand times x (d ln x)
    seg = 0.5 * (f[1:] + f[:-1]) * np.diff(np.log(xs))
    F = np.concatenate([np.cumsum(seg[::-1])[::-1], [0.0]])
    out = []
    for p in pressures:
        x0 = np.clip(w * p / Es, xs[0], xs[-1])
        inner = np.interp(np.log(x0), np.log(xs), F)
        # int dq q^2 C w (...) = (1 / 2 pi) sum q C w (...) dq2
        out.append(math.sqrt(math.pi) * float(np.sum(q * C * w * inner * dq2)) / (2 * np.pi))
    return out


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 512
    seeds = int(sys.argv[2]) if len(sys.argv) > 2 else 3
    out = sys.argv[3] if len(sys.argv) > 3 else None
    dx, Es = 1e-6, 1e9
    scaled = [0.005, 0.01, 0.02, 0.03, 0.05]
    rows = []
    for seed in range(1, seeds + 1):
        h, g, nayak = surface(n, dx, seed)
        t = time.perf_counter()
        curve = frictal.contact(h, spacing=dx, pressure=[s * Es * g for s in scaled], modulus=Es, poisson=0.0,
                                detrend="none", periodic=True, stiffness=False, fields=True)
        wall = time.perf_counter() - t
        persson = persson_separation(h, dx, [s * Es * g for s in scaled], Es)
        hrms = float(np.sqrt(np.mean((h - h.mean()) ** 2)))
        for s, r, up in zip(scaled, curve, persson):
            ac = corrected_area(r["pressure"])
            rows.append((seed, nayak, s, r["contact_area_fraction"], r["contact_area_fraction"] / s, ac, ac / s,
                         r["iterations"], r["mean_separation"] / hrms, up / hrms))
        rows.append((seed, nayak, None, None, None, None, None, wall, None, None))
    lines = [f"# Rough contact: relative area against load ({datetime.date.today()}, {platform.node()})", "",
             f"bench/contact_rough.py {n} {seeds}: periodic {n} x {n} self-affine maps, Hurst 0.8, roll-off L/4, "
             "short cutoff 16 spacings; kappa = (A/A0) / (p / (E* g)); A*: the area corrected for its perimeter "
             "(Yastrebov, Anciaux & Molinari 2017, Tribol. Int.), kappa* = (A*/A0) / (p / (E* g)).", "",
             "| seed | Nayak alpha | p / (E* g) | A / A0 | kappa | A* / A0 | kappa* | iterations | u / h_rms | "
             "Persson u / h_rms |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    kappas, kcorr, ratios = [], [], []
    for seed, nayak, s, a, k, ac, kc, it, u, up in rows:
        if s is None:
            lines.append(f"| {seed} | | curve of {len(scaled)} loads: {it:.1f} s wall | | | | | | | |")
            continue
        kappas.append(k)
        kcorr.append(kc)
        ratios.append(u / up)
        lines.append(f"| {seed} | {nayak:.1f} | {s:.3f} | {a:.4f} | {k:.3f} | {ac:.4f} | {kc:.3f} | {it} | {u:.3f} | "
                     f"{up:.3f} |")
    lines += ["", f"kappa over all: {min(kappas):.3f} .. {max(kappas):.3f} (mean {np.mean(kappas):.3f}); "
              f"corrected kappa*: {min(kcorr):.3f} .. {max(kcorr):.3f} (mean {np.mean(kcorr):.3f}); "
              "Persson sqrt(8/pi) = 1.596, Bush-Gibson-Thomas sqrt(2 pi) = 2.507.",
              f"mean separation / Persson's: {min(ratios):.3f} .. {max(ratios):.3f} (mean {np.mean(ratios):.3f})."]
    text = "\n".join(lines) + "\n"
    print(text)
    if out:
        with open(out, "w") as f:
            f.write(text)


if __name__ == "__main__":
    main()
