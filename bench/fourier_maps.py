"""Fourier-filtered random self-affine maps for the bench scripts (areal_tilt_pairs.py,
make_map_pairs.py, predict_vs_sim_pairs.py): one definition. Heights in metres."""
import numpy as np


def fourier_map(n, a, seed, H=0.8, stretch=(1.0, 1.0), rms_slope=0.2, qmin_cells=8, qmax_cells=2.5):
    """n x n heights on spacing a (m): flat spectrum below the roll-off wavelength qmin_cells * a,
    q^-(1+H) above it up to qmax_cells * a, none beyond; cut from a field periodic on 2n (so not
    periodic); mean 0, rms slope `rms_slope`. stretch scales qx, qy (anisotropy)."""
    rng = np.random.default_rng(seed)
    N = 2 * n  # periodic on 2n, cut n x n (not periodic)
    qx = np.fft.fftfreq(N, a)[None, :] * 2 * np.pi
    qy = np.fft.fftfreq(N, a)[:, None] * 2 * np.pi
    q = np.sqrt((qx * stretch[0]) ** 2 + (qy * stretch[1]) ** 2)
    qr = 2 * np.pi / (qmin_cells * a); qs = 2 * np.pi / (qmax_cells * a)
    amp = np.where(q < qr, qr ** (-(1 + H)), np.where(q > qs, 0.0, np.maximum(q, 1e-30) ** (-(1 + H))))
    amp[0, 0] = 0
    z = np.real(np.fft.ifft2(amp * (rng.normal(size=(N, N)) + 1j * rng.normal(size=(N, N)))))[:n, :n]
    z -= z.mean()
    gy, gx = np.gradient(z, a)
    s = np.sqrt(np.mean(gx ** 2 + gy ** 2))
    return z * rms_slope / s
