"""Signature functions of K0-K3 at alpha = 5 deg (paper Fig. 4), theta/alpha against the offset. Drawn by the theory page at build time."""
import numpy as np, matplotlib.pyplot as plt, frictal
from frictal import plots
alpha = np.radians(5)
fig, axes = plt.subplots(1, 4, figsize=(9, 2.6), sharey=True)
for n, ax in enumerate(axes):
    sig = frictal.signature(frictal.koch_profile(iterations=n, alpha=alpha))
    plots.plot_signature(sig, ax=ax, normalise=alpha, lw=0.8)
    ax.set_title(f"K{n}: θmax/α = {sig['theta_max_forward'] / alpha:.3f}", fontsize=9)
    ax.set_xlabel("offset (m)", fontsize=8)
    ax.tick_params(labelsize=7)
    ax.ticklabel_format(axis="x", style="sci", scilimits=(0, 0))
for ax in axes[1:]:
    ax.set_ylabel("")
