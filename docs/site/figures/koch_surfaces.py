"""Koch surfaces K0-K3 at alpha = 20 deg, and a folded K1 curve with its upper envelope. Drawn by the theory page at build time."""
import numpy as np, matplotlib.pyplot as plt, frictal
fig, axes = plt.subplots(1, 2, figsize=(8, 3.0))
for n in range(4):
    k = frictal.koch_profile(iterations=n, alpha=np.radians(20), length=0.02)
    axes[0].plot(np.asarray(k.x) * 1e3, np.asarray(k.z) * 1e3 + 1.2 * n, lw=0.9, label=f"K{n}")
axes[0].set(xlabel="x (mm)", ylabel="z (mm), shifted", title="Koch surfaces, α = 20°")
axes[0].legend(fontsize=7, loc="upper right")
x, z = frictal.koch_curve(iterations=1, alpha=np.radians(50), length=0.01)
env = frictal.upper_envelope(x, z)
axes[1].plot(np.asarray(x) * 1e3, np.asarray(z) * 1e3, lw=2.5, color="0.8", label="K1 curve (folds over)")
axes[1].plot(np.asarray(env.x) * 1e3, np.asarray(env.z) * 1e3, lw=0.9, color="C3", label="upper envelope")
axes[1].set(xlabel="x (mm)", ylabel="z (mm)", title="α = 50°: curve and profile")
axes[1].legend(fontsize=7, loc="lower right")
