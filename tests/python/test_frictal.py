"""Python package tests: expectations from the paper and closed forms, not from frictal's output."""
import math
import os

import numpy as np
import pytest

import frictal


@pytest.mark.parametrize("n,mult", [(0, 1), (1, 1), (2, 2), (3, 3)])
def test_koch_signature_is_n_alpha(n, mult):
    alpha = np.radians(10)
    sig = frictal.signature(frictal.koch_profile(iterations=n, alpha=alpha))
    assert sig["theta_max_forward"] == pytest.approx(mult * alpha, abs=1e-12)
    assert sig["theta_max_backward"] == pytest.approx(mult * alpha, abs=1e-12)
    assert sig["exact"]


def test_signature_spheroradius_keyword():
    # K0 at 20 deg (lambda = 0.01 m) with r = 0.01 m: the rounded tips make the lift an arc whose
    # steepest contact is asin(lambda / (4 r)) = asin(0.25) (closed form, test_sphero.cpp); none
    # (None, the table's default) is the rigid signature itself, and r itself is > 0 (the tilt
    # test's field: one range).
    k0 = frictal.koch_profile(iterations=0, alpha=np.radians(20))
    rigid = frictal.signature(k0)
    assert frictal.signature(k0, spheroradius=None)["theta_max_forward"] == rigid["theta_max_forward"]
    with pytest.raises(ValueError, match="spheroradius: expected a number > 0 m, got 0"):
        frictal.signature(k0, spheroradius=0.0)
    sig = frictal.signature(k0, spheroradius=0.01)
    assert sig["spheroradius"] == 0.01
    assert sig["theta_max_forward"] == pytest.approx(math.asin(0.25), abs=1e-9)
    with pytest.raises(ValueError, match="spheroradius"):
        frictal.signature(k0, spheroradius=-1.0)

def test_lift_matches_reference_and_numpy_scan():
    f = frictal.wm_profile(n_max=5, seed=3)
    g = frictal.wm_profile(n_max=5, seed=4)
    up = frictal.rotate180(g)
    sig = frictal.signature(f, g, detrend="none")  # the generated heights as they are
    fz, gz = np.asarray(f.z), np.asarray(up.z)
    dx = f.x[1] - f.x[0]
    for i in range(0, len(sig["offset"]), 50):
        s = sig["offset"][i]
        k = int(round(s / dx))
        # aligned grids: h(s) = max_i f[i] - g[i - k] (independent numpy scan)
        assert sig["lift"][i] == pytest.approx(np.max(fz[k:] - gz[: len(gz) - k]), abs=1e-22)
        assert sig["lift"][i] == pytest.approx(frictal.lift_direct(f, up, s), abs=1e-22)


def test_wm_rms_and_points():
    p = frictal.wm_profile()
    assert len(p) == 11534
    x, z = np.asarray(p.x), np.asarray(p.z)
    # rms about the mean of the piecewise-linear profile, by numpy: exact segment integrals
    dx = np.diff(x)
    mean = np.sum(dx * (z[1:] + z[:-1]) / 2) / (x[-1] - x[0])
    a, b = z[:-1] - mean, z[1:] - mean
    rms = math.sqrt(np.sum(dx * (a * a + a * b + b * b) / 3) / (x[-1] - x[0]))
    assert rms == pytest.approx(1e-9, rel=1e-9)
    assert frictal.profile_stats(p)["rms_height"] == pytest.approx(rms, rel=1e-12)


def test_friction_eq6_eq18():
    f = frictal.predict_friction(math.tan(np.radians(10)), np.radians(20), np.radians(3))
    assert np.degrees(f["upper_bound_friction_angle"]) == pytest.approx(30)
    assert f["upper_bound_friction_coefficient"] == pytest.approx(math.tan(np.radians(30)))
    assert np.degrees(f["eq18_low_friction_angle"]) == pytest.approx(27)


def test_errors_are_value_errors():
    with pytest.raises(ValueError, match="alpha"):
        frictal.koch_profile(alpha=np.radians(70))
    with pytest.raises(ValueError, match="at least 2"):
        frictal.Profile([0.0], [0.0])
    with pytest.raises(ValueError, match="non-decreasing"):
        frictal.Profile([0.0, 2.0, 1.0], [0.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="exponent"):
        frictal.wm_profile(exponent="bogus")


def test_folded_koch_envelope_and_roundtrip(tmp_path):
    x, z = frictal.koch_curve(iterations=1, alpha=np.radians(50), length=0.02)
    assert np.any(np.diff(x) < 0)  # folds over
    env = frictal.upper_envelope(x, z)
    assert np.all(np.diff(env.x) >= 0)
    path = os.path.join(tmp_path, "env.csv")
    frictal.write_profile_csv(path, env)
    back = frictal.read_profile(path)
    assert np.array_equal(np.asarray(back.x), np.asarray(env.x))
    assert np.array_equal(np.asarray(back.z), np.asarray(env.z))


def test_plots_render(tmp_path):
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from frictal import plots

    sig = frictal.signature(frictal.koch_profile(iterations=2, alpha=np.radians(5)))
    fig, axes = plt.subplots(3)
    plots.plot_signature(sig, ax=axes[0], normalise=np.radians(5))
    plots.plot_slope_pdf(sig, ax=axes[1])
    plots.plot_profile(frictal.koch_profile(iterations=2), ax=axes[2])
    out = os.path.join(tmp_path, "p.png")
    fig.savefig(out)
    assert os.path.getsize(out) > 1000


def test_tilt_flat_blocks_slide_at_atomic_friction_angle():
    # Paper Eq. 6 with theta = 0: flat blocks slide at atan(mu_a). The upper block is shifted by
    # 1 cm so that no corner sits on a corner (docs/dem.md).
    x = np.array([0.0, 0.1])
    z = np.array([0.0, 0.0])
    lower = frictal.Profile(x, z)
    r = frictal.tilt(lower, atomic_friction=0.3, period=0.01, initial_offset=0.01)
    assert r["slid"]
    assert np.degrees(r["friction_angle"]) == pytest.approx(np.degrees(np.arctan(0.3)), abs=0.1)
    s = r["series"]
    assert len(s["time"]) == len(s["tilt"]) > 10
    with pytest.raises(ValueError, match="face"):
        frictal.tilt(lower, face="bogus", initial_offset=0.01)
    with pytest.raises(TypeError):
        frictal.tilt("not a surface")


def test_tilt_threads_change_nothing():
    # The thread count is a keyword outside the settings table; the result is the same bit for bit.
    k2 = frictal.koch_profile(iterations=2, alpha=np.radians(20), length=0.05)
    one = frictal.tilt(k2, max_tilt=np.radians(2))
    two = frictal.tilt(k2, max_tilt=np.radians(2), threads=2)
    # No slide below 2 deg: friction_angle is None (null in `frictal tilt --json`) in both.
    assert not one["slid"] and not two["slid"]
    assert one["friction_angle"] is None and two["friction_angle"] is None and one["steps"] == two["steps"]
    for key in ("time", "normal_force", "tangential_force", "displacement", "velocity"):
        assert np.array_equal(one["series"][key], two["series"][key])
    assert "threads" not in [f["name"] for f in frictal.tilt_settings()]
    with pytest.raises(ValueError, match="threads"):
        frictal.tilt(k2, threads=-1)
    # A generated surface states what was given: a repeating Profile, its period, length and points.
    assert one["surface"] == {"generator": "a repeating Profile", "period": k2.period,
                              "length": k2.x[-1] - k2.x[0], "points": len(k2.x)}
    assert frictal.tilt(frictal.koch_curve(iterations=1), max_tilt=np.radians(1))["surface"]["generator"] == (
        "an (x, z) curve")


def test_tilt_reports_both_predictions_and_holds_rotation():
    # K0 at 10 deg: rigid and rounded blocks both predict alpha (the flanks survive a small r,
    # docs/dem.md); with the rotation held the block slides at alpha and does not turn.
    k0 = frictal.koch_profile(iterations=0, alpha=np.radians(10), length=0.05)
    r = frictal.tilt(k0, hold_rotation=True, spheroradius=5e-5)
    assert r["predicted_friction_angle"] == pytest.approx(np.radians(10), abs=1e-12)
    assert r["predicted_sphero_friction_angle"] == pytest.approx(np.radians(10), abs=1e-9)
    assert r["rotation_before_slide"] == 0
    assert np.degrees(r["friction_angle"]) == pytest.approx(10, abs=0.1)
    assert r["warnings"] == []
    assert r["scales"]["spheroradius"] == 5e-5
    # A tiny spheroradius: the resting overlap W/k_n is no longer small against r.
    small = frictal.tilt(k0, spheroradius=1e-7, max_tilt=np.radians(1))
    assert "core-overlap" in [w["code"] for w in small["warnings"]]


def test_hold_angle_reference_wm_pair_and_sawtooth():
    # The reference WM pair: an independent numpy computation of the exact rigid lift gives, from a drop
    # at 23.79 mm with d = 1 cm, phi_qs = 1.549 deg and phi_in = 0.695 deg.
    kw = dict(dimension=1.5, n_max=6, longest_wavelength=0.01, length=0.2, rms_height=1e-5)
    f, g = frictal.wm_profile(seed=1, **kw), frictal.wm_profile(seed=2, **kw)
    h = frictal.hold_angle(f, g, runaway_distance=0.01, start_offset=0.02379, detrend="none")
    assert np.degrees(h["start"]["hold_angle"]) == pytest.approx(1.549, abs=0.0015)
    assert np.degrees(h["start"]["inertial_hold_angle"]) == pytest.approx(0.695, abs=0.0015)
    fw = h["forward"]
    assert fw["basins"]["weight"].sum() == pytest.approx(f.x[-1] / 2, rel=1e-9)  # the drops cover [0, L/2]
    assert fw["hold_angle"]["q05"] <= fw["hold_angle"]["q50"] <= fw["hold_angle"]["q95"]
    # A periodic sawtooth against itself turned over: every drop holds at the rise angle forwards,
    # at the fall angle atan(tan 25 deg * 0.7 / 0.3) backwards, whatever d (closed forms).
    saw = frictal.sawtooth_profile(rise_angle=np.radians(25), rise_fraction=0.7)
    hs = frictal.hold_angle(saw, atomic_friction=0.2)
    assert hs["runaway_distance"] == pytest.approx(0.01)  # one period
    assert hs["forward"]["hold_angle"]["min"] == pytest.approx(np.radians(25) + math.atan(0.2), abs=1e-9)
    fall = math.atan(math.tan(np.radians(25)) * 0.7 / 0.3)
    assert hs["backward"]["hold_angle"]["max"] == pytest.approx(fall + math.atan(0.2), abs=1e-9)
    with pytest.raises(ValueError, match="start offset"):
        frictal.hold_angle(f, g, start_offset=0.5, detrend="none")
