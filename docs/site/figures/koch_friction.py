"""Predicted friction angle (Eq. 6, mu_a = 0) of K0-K3 against alpha (the theory of paper Fig. 6). Drawn by the theory page at build time."""
import numpy as np, matplotlib.pyplot as plt, frictal
limits = {0: 60, 1: 45, 2: 30, 3: 22.5}
fig, ax = plt.subplots(figsize=(6, 3.4))
for n in range(4):
    alphas = np.linspace(2.5, limits[n], 10)
    phi = []
    for a in alphas:
        sig = frictal.signature(frictal.koch_profile(iterations=n, alpha=np.radians(a)))
        phi.append(np.degrees(frictal.predict_friction(0.0, sig["theta_max_forward"])["upper_bound_friction_angle"]))
    ax.plot(alphas, phi, "o-", ms=3, lw=0.9, label=f"K{n}")
ax.set(xlabel="base angle α (deg)", ylabel="predicted friction angle φ (deg)", title="Eq. 6 on Koch surfaces (μa = 0)")
ax.legend(fontsize=8)
