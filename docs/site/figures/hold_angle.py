"""The hold angle of a Weierstrass-Mandelbrot pair (D = 1.5, n_max = 6, lambda = 0.01 m, L_b = 0.2 m,
rms 10 um, seeds 1 and 2; d = 1 cm): the lift h(s) with the rest offsets of its basins, and the
distribution of phi_qs and phi_in over drops against theta_max and Eq. 18's range. Drawn by the
theory page at build time."""
import numpy as np, matplotlib.pyplot as plt, frictal
wm = dict(dimension=1.5, n_max=6, longest_wavelength=0.01, length=0.2, rms_height=1e-5)
lower, upper = frictal.wm_profile(seed=1, **wm), frictal.wm_profile(seed=2, **wm)
sig = frictal.signature(lower, upper)
hold = frictal.hold_angle(lower, upper, runaway_distance=0.01)
fw = hold["forward"]
basins = fw["basins"]
fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(10, 3.4), gridspec_kw={"width_ratios": [1.4, 1]})
s, h = np.asarray(hold["offset"]), np.asarray(hold["lift"])
ax0.plot(s * 1e3, h * 1e6, lw=0.7, label="lift h(s)")
rest = np.asarray(basins["rest_offset"])
ax0.plot(rest * 1e3, np.interp(rest, s, h) * 1e6, "v", ms=3, color="C3", label="rest offsets of the basins")
ax0.set(xlabel="offset s (mm)", ylabel="h (µm)", title="the lift the upper block moves on")
ax0.legend(fontsize=7, loc="upper left")
w = np.asarray(basins["weight"])
bins = np.linspace(0, np.degrees(sig["theta_max_forward"]) * 1.1, 40)
ax1.hist(np.degrees(basins["hold_angle"]), bins=bins, weights=w / w.sum(), alpha=0.7, label="φ_qs (quasi-static)")
ax1.hist(np.degrees(basins["inertial_hold_angle"]), bins=bins, weights=w / w.sum(), alpha=0.5, label="φ_in (inertial)")
tm, sd = np.degrees(sig["theta_max_forward"]), np.degrees(sig["contact_slope_std"])
ax1.axvspan(tm - sd, tm, color="0.85", zorder=0, label="Eq. 18 range")
ax1.axvline(tm, color="k", lw=0.8, ls="--", label="θmax")
ax1.set(xlabel="angle (deg), μa = 0", ylabel="fraction of drops", title="over drops (d = 1 cm)")
ax1.legend(fontsize=7, loc="upper left")
