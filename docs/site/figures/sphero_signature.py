"""Signature of K2 (alpha = 20 deg) for rigid blocks and for spheropolygons of two radii. Drawn by the theory page at build time."""
import numpy as np, matplotlib.pyplot as plt, frictal
k = frictal.koch_profile(iterations=2, alpha=np.radians(20))
fig, ax = plt.subplots(figsize=(6.5, 3.2))
for r in [0.0, 2e-4, 5e-4]:
    sig = frictal.signature(k, spheroradius=r)
    label = "rigid" if r == 0 else f"r = {r * 1e3:g} mm"
    ax.plot(np.asarray(sig["offset"]) * 1e3, np.degrees(sig["theta"]), lw=0.9,
            label=f"{label}: θmax = {np.degrees(sig['theta_max_forward']):.2f}°")
ax.set(xlabel="offset (mm)", ylabel="contact slope θ (deg)", title="K2, α = 20°: rigid and rounded blocks")
ax.legend(fontsize=8)
