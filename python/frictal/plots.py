"""Matplotlib plots of frictal results (optional: imports matplotlib on use)."""
import numpy as np


def _axes(ax):
    if ax is None:
        import matplotlib.pyplot as plt

        _, ax = plt.subplots()
    return ax


def plot_profile(profile, ax=None, scale=1e6, **kw):
    """Profile z(x), in micrometres by default (scale=1e6)."""
    ax = _axes(ax)
    ax.plot(np.asarray(profile.x) * scale, np.asarray(profile.z) * scale, **kw)
    ax.set_xlabel("x (µm)" if scale == 1e6 else "x")
    ax.set_ylabel("z (µm)" if scale == 1e6 else "z")
    return ax


def plot_signature(sig, ax=None, normalise=None, **kw):
    """theta(x_ofs) in degrees, drawn as its exact pieces between evaluated offsets.

    normalise: divide theta by this angle (radians), e.g. alpha for Koch surfaces (Fig. 4)."""
    ax = _axes(ax)
    s = np.asarray(sig["offset"])
    left, right = np.asarray(sig["theta_left"]), np.asarray(sig["theta_right"])
    xs = np.repeat(s, 2)[1:-1]
    ys = np.column_stack([right[:-1], left[1:]]).ravel()
    unit = normalise if normalise else np.pi / 180
    ax.plot(xs, ys / unit, **kw)
    ax.set_xlabel("offset x_ofs (m)")
    ax.set_ylabel("θ / α" if normalise else "contact slope θ (deg)")
    return ax


def plot_slope_pdf(sig, ax=None, **kw):
    """Probability density of contact slopes (per degree)."""
    ax = _axes(ax)
    pdf = sig["contact_slope_pdf"]
    edges = np.degrees(np.asarray(pdf["edges"]))
    ax.stairs(np.asarray(pdf["density"]) * np.pi / 180, edges, **kw)
    ax.set_xlabel("contact slope (deg)")
    ax.set_ylabel("density (1/deg)")
    return ax
