"""frictal.predict: the one answer, from paths, Profile objects and numpy arrays, against closed
forms (a sawtooth's flanks) and with its warnings issued as warnings.warn categories."""
import math
import os
import warnings

import numpy as np
import pytest

import frictal

DATA = os.path.join(os.path.dirname(__file__), "..", "data")


def sawtooth(rise_deg=25.0, fraction=0.7, wavelength=0.01, periods=20):
    return frictal.sawtooth_profile(rise_angle=math.radians(rise_deg), rise_fraction=fraction,
                                    wavelength=wavelength, length=wavelength * periods)


def test_sawtooth_against_itself_holds_at_its_rising_flank():
    # Mated teeth: every drop slides forward when the tilt passes the rising flank, 25 deg (by hand),
    # plus atan(mu_a) (Eq. 6); backward the falling flank, atan(tan 25 deg * 0.7 / 0.3).
    saw = sawtooth()
    p = frictal.predict(saw, detrend="none", atomic_friction=0.1)
    want = math.radians(25) + math.atan(0.1)
    assert p.friction_angle == pytest.approx(want, abs=1e-9)
    assert p.friction_angle_q05 == pytest.approx(want, abs=1e-9)
    assert p.friction_angle_q95 == pytest.approx(want, abs=1e-9)
    assert p.upper_bound_friction_angle == pytest.approx(want, abs=1e-9)
    assert p.model == "profile-quasi-static-hold"
    d = p.to_dict()
    assert d["friction_angle_deg"] == pytest.approx(math.degrees(want), abs=1e-7)
    b = frictal.predict(saw, detrend="none", direction=math.pi)
    assert b.friction_angle == pytest.approx(math.atan(math.tan(math.radians(25)) * 0.7 / 0.3), abs=1e-9)


def test_to_dict_has_every_declared_column():
    p = frictal.predict(sawtooth(), detrend="none")
    keys = [k for k, _unit, _help in frictal.prediction_columns()]
    assert list(p.to_dict().keys()) == keys + ["warnings"]


def test_path_profile_and_array_give_the_same_numbers():
    path = os.path.join(DATA, "profiles", "dektak-1.csv")
    a = frictal.predict(path)
    s = frictal.read_surface(path)
    b = frictal.predict(frictal.Profile(s["x"], s["z"]))
    assert a.friction_angle == b.friction_angle
    assert a.upper_bound_friction_angle == b.upper_bound_friction_angle
    assert a.form == "line"
    assert a.conditioning == "form: line"
    # A uniform grid as a numpy array with its spacing: the same as the Profile on that grid.
    z = np.sin(np.linspace(0, 40 * np.pi, 2001)) * 1e-5
    x = np.arange(z.size) * 1e-5
    c = frictal.predict(z, spacing=1e-5)
    d = frictal.predict(frictal.Profile(x, z))
    assert c.friction_angle == d.friction_angle


def test_a_map_as_a_numpy_array():
    # Grooves across x mate with themselves turned over; the free block climbs the steepest segment
    # of the piecewise-linear grooves from every drop: atan(A sin(2 pi / m) / a) (by hand).
    n, m, a, amp = 24, 8, 1e-3 / 23, 2.4e-5
    h = np.tile(amp * np.sin(2 * np.pi * np.arange(n) / m), (n, 1))
    p = frictal.predict(h, spacing=a, detrend="none", drops=2)
    want = math.atan(amp * math.sin(2 * math.pi / m) / a)
    assert p.model == "map-continuous-free"
    assert p.drops == 4
    assert want - 1e-9 <= p.friction_angle_min and p.friction_angle_max <= want + 2e-4


def test_unit_mix_up_is_warned_with_its_category():
    path = os.path.join(DATA, "profiles", "csv-1.csv")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        p = frictal.predict(path)
    codes = {w.code for w in p.warnings}
    assert "units-suspect" in codes
    assert any(issubclass(w.category, frictal.UnitsSuspectWarning) for w in caught)
    assert issubclass(frictal.UnitsSuspectWarning, frictal.FrictalWarning)


def test_bad_input_raises_naming_the_value():
    with pytest.raises(ValueError, match="90 deg"):
        frictal.predict(sawtooth(), direction=math.pi / 2)
    with pytest.raises(ValueError, match="spacing"):
        frictal.predict(np.zeros(10))
    with pytest.raises(ValueError, match="two profiles or two maps"):
        frictal.predict(sawtooth(), np.zeros((4, 4)), spacing=1e-6)


def test_every_function_returns_and_issues_its_warnings():
    """Issue "No silent nonsense": the plausibility codes reach every Python function that computes
    from a surface, in the result's ``warnings`` and through warnings.warn with the code's category.
    A sine of 1 um on 1 mm (rms slope 0.02: plausible) gives none; one point 100 um up (70 rms
    heights off its neighbours) is a spike; Eq. 18 with sigma above theta_max clamps its low end."""
    import warnings

    x = np.linspace(0, 1e-3, 400)
    z = 1e-6 * np.sin(2 * np.pi * x / 2e-4)
    clean = frictal.Profile(x, z)
    z2 = z.copy()
    z2[200] = 1e-4
    spiky = frictal.Profile(x, z2)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        assert frictal.signature(clean)["warnings"] == []
        assert frictal.profile_stats(clean)["warnings"] == []
        assert frictal.predict_friction(0.0, 0.2, 0.1)["warnings"] == []
    assert not [w for w in caught if issubclass(w.category, frictal.FrictalWarning)]
    with pytest.warns(frictal.SpikesWarning):
        r = frictal.signature(spiky)
    assert "spikes" in [w["code"] for w in r["warnings"]]
    with pytest.warns(frictal.Eq18LowClampedWarning):
        f = frictal.predict_friction(0.0, 0.01, 0.05)
    assert f["eq18_low_friction_angle"] == 0.0 and f["eq18_low_clamped"]
    heights = np.tile(z2[150:250], (20, 1))
    with pytest.warns(frictal.SpikesWarning):
        m = frictal.anisotropy(heights, dx=x[1], dy=x[1], directions=2, lines=4)
    assert "upper_bound_friction_angle" in m and "friction_angle" not in m


def _spiky_sine(n=1001, h=1e-6, amplitude=1e-6, wavelength=2e-4, spikes=(250, 500, 753)):
    # A sine with spikes of +-20 um (about 15 Sq from their neighbours' median), and the profile
    # the filter must give: each spike's point on the line between its neighbours (their mean).
    x = np.arange(n) * h
    z = amplitude * np.sin(2 * np.pi * x / wavelength)
    reference = z.copy()
    for i in spikes:
        reference[i] = 0.5 * (z[i - 1] + z[i + 1])
    spiky = reference.copy()
    spiky[list(spikes)] += np.array([2e-5, -2e-5, 2e-5])[: len(spikes)]
    return x, spiky, reference


def test_condition_crops_removes_spikes_and_records_each_step():
    x, spiky, reference = _spiky_sine()
    out, rec = frictal.condition(frictal.Profile(x, spiky), crop=(1e-4, 9e-4), remove_spikes=True, detrend="none")
    assert len(out.x) == 801  # x = 100 .. 900 um
    assert out.x[0] == x[100] and out.x[-1] == x[900]
    np.testing.assert_allclose(out.z, reference[100:901], rtol=0, atol=1e-20)
    assert rec["spikes_removed"] == 3
    assert rec["points_after"] == (801, 1)
    assert rec["text"] == ("crop x [0.0001, 0.0009] m: kept 801 of 1001 points; spikes (k = 10 Sq): 3 points removed "
                           "(replaced by linear interpolation); form: none")
    # By default the form of every front end: a line, the trapezoid-weighted least-squares line
    # (numpy's weighted fit; polyfit's w multiplies the residuals, hence the square root).
    line, rec = frictal.condition(frictal.Profile(x, spiky), crop=(1e-4, 9e-4), remove_spikes=True)
    assert rec["form"] == "line" and rec["text"].endswith("form: line")
    xs, zs = np.asarray(x[100:901]), np.asarray(reference[100:901])
    w = np.zeros_like(xs)
    w[1:] += 0.5 * np.diff(xs)
    w[:-1] += 0.5 * np.diff(xs)
    fit = np.polyfit(xs, zs, 1, w=np.sqrt(w))
    np.testing.assert_allclose(line.z, zs - np.polyval(fit, xs), rtol=0, atol=1e-15)
    # The CLI's text form of the window reads the same.
    same, _ = frictal.condition(frictal.Profile(x, spiky), crop="0.1mm,0.9mm")
    assert len(same.x) == 801
    with pytest.raises(ValueError, match="crop"):
        frictal.condition(frictal.Profile(x, spiky), crop=(5e-3, 6e-3))
    with pytest.raises(ValueError, match="crop"):
        frictal.condition(frictal.Profile(x, spiky), crop=(1e-4,))
    with pytest.raises(ValueError, match="spike_threshold: expected a number > 0, got 0"):
        frictal.condition(frictal.Profile(x, spiky), remove_spikes=True, spike_threshold=0)


def test_condition_of_a_file_as_read_is_the_clis():
    # condition(read_surface(path)) conditions a file as every CLI command does by default: the
    # profile's line (plane for a map) removed, stated in the record; the same heights as `frictal
    # signature`/`stats` analyse, checked here against the library's own detrend on the raw profile
    # and against `predict`'s record of the same file.
    path = os.path.join(DATA, "profiles", "dektak-1.csv")
    raw = frictal.read_surface(path)
    out, rec = frictal.condition(raw)
    assert rec["form"] == "line" and rec["text"] == "form: line"
    ref = frictal.detrend(frictal.Profile(raw["x"], raw["z"]), "line")
    np.testing.assert_array_equal(out.z, ref.z)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        assert frictal.predict(path).conditioning == rec["text"]
    m, mrec = frictal.condition(frictal.read_map(os.path.join(DATA, "x3p", "x3p-2.x3p")))
    assert mrec["text"] == "form: plane"
    assert abs(np.nanmean(m["heights"])) < 1e-6 * np.nanstd(m["heights"])


def test_condition_keeps_a_maps_mask():
    ny, nx = 30, 40
    yy, xx = np.mgrid[0:ny, 0:nx]
    h = 1e-3 * xx * 1e-6 + 1e-7 * np.sin(2 * np.pi * xx / 8)
    h[4, 3] = np.nan
    h[5, 8] += 2e-5
    out, rec = frictal.condition({"heights": h, "dx": 1e-6, "dy": 1e-6}, crop=(2e-6, 33e-6, 3e-6, 22e-6),
                                 remove_spikes=True, detrend="plane")
    m = out["heights"]
    assert m.shape == (20, 32)
    assert out["x0"] == pytest.approx(2e-6) and out["y0"] == pytest.approx(3e-6)
    assert np.isnan(m[4 - 3, 3 - 2]) and np.isnan(m[5 - 3, 8 - 2])
    assert np.count_nonzero(np.isnan(m)) == 2
    assert rec["spikes_removed"] == 1 and rec["form"] == "plane"


def test_predict_with_spikes_removed_reads_the_clean_profile():
    x, spiky, reference = _spiky_sine()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        a = frictal.predict(frictal.Profile(x, spiky))
    assert any(issubclass(w.category, frictal.SpikesWarning) for w in caught)
    assert a.spikes_removed == 0
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        b = frictal.predict(frictal.Profile(x, spiky), remove_spikes=True)
    assert not any(issubclass(w.category, frictal.SpikesWarning) for w in caught)
    c = frictal.predict(frictal.Profile(x, reference))
    assert b.spikes_removed == 3
    assert b.conditioning == "spikes (k = 10 Sq): 3 points removed (replaced by linear interpolation); form: line"
    assert b.to_dict()["spikes_removed"] == 3
    assert b.friction_angle == pytest.approx(c.friction_angle, abs=1e-12)
    assert b.theta_max == pytest.approx(c.theta_max, abs=1e-12)
    d = frictal.predict(frictal.Profile(x, spiky), remove_spikes=True, crop=(5e-5, 9.5e-4))
    assert d.conditioning.startswith("crop x [5e-05, 0.00095] m: kept 901 of 1001 points; spikes")
    with pytest.raises(ValueError, match="crop"):
        frictal.predict(frictal.Profile(x, spiky), crop=(1.0, 2.0))


def test_a_bound_below_zero_is_warned_in_python_too():
    # predict_friction of theta_max = -0.1 rad: mu = tan(-0.1) < 0, bound-negative; and
    # signature() of a flat block on a ramp descending along +x (every contact slope < 0).
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        r = frictal.predict_friction(0.0, -0.1, 0.01)
    assert "bound-negative" in {w["code"] for w in r["warnings"]}
    assert any(issubclass(w.category, frictal.BoundNegativeWarning) for w in caught)
    assert not frictal.check_friction_bound(0.2)
    ramp = frictal.Profile(np.arange(1001) * 1e-4, -0.1 * np.arange(1001) * 1e-4)
    flat = frictal.Profile(np.arange(15) * 0.7e-4, np.zeros(15))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        s = frictal.signature(ramp, flat, detrend="none")  # the ramp kept: its descent is the point
    assert math.atan(-0.1) - 1e-12 <= s["theta_max_forward"] < 0
    assert "bound-negative" in {w["code"] for w in s["warnings"]}


def test_the_stated_test_takes_lengths_and_returns_the_d_sweep():
    # A sine of 64 points a wavelength over 80 wavelengths, not periodic: its slope correlation
    # length is lambda acos(1/e) / (2 pi) (the slope is a cosine; by hand), so the default d is
    # 12.5 of it and the block 20 d; the scan holds that test (80 > 0.192 * 12.5 * 28 = 67 wavelengths).
    lam = 0.01
    x = np.arange(80 * 64 + 1) * lam / 64
    prof = frictal.Profile(x, 1e-6 * np.sin(2 * np.pi * x / lam))
    p = frictal.predict(prof, detrend="none")
    d = 12.5 * lam * math.acos(math.exp(-1)) / (2 * math.pi)
    assert p.runaway_distance == pytest.approx(d, rel=2e-3)
    # the block: 20 d to the nearest samples (within one sampling interval, lam / 64)
    assert p.block_length == pytest.approx(20 * p.runaway_distance, abs=lam / 64 * (1 + 1e-9))
    assert list(p.d_sweep) == pytest.approx([k * p.runaway_distance for k in (0.25, 0.5, 1, 2, 4)])
    assert p.d_sweep_median[2] == p.friction_angle  # the headline is the sweep's entry at d
    dd = p.to_dict()
    assert dd["d_sweep_median_deg"][2] == pytest.approx(math.degrees(p.friction_angle))
    # Stated lengths are kept; 'whole' slides the whole profile over the first half of the other.
    q = frictal.predict(prof, detrend="none", runaway_distance=0.004, block_length=0.08)
    assert (q.runaway_distance, q.block_length) == pytest.approx((0.004, 0.08))
    w = frictal.predict(prof, detrend="none", runaway_distance=0.004, block_length="whole")
    assert w.block_length == pytest.approx(x[-1])
    with pytest.raises(ValueError, match="block_length"):
        frictal.predict(prof, block_length="half")


def test_a_short_scan_is_warned_with_its_category():
    lam = 0.01
    x = np.arange(4 * 64 + 1) * lam / 64  # four wavelengths: too short for the default test
    with pytest.warns(frictal.ScanTooShortWarning):
        p = frictal.predict(frictal.Profile(x, 1e-6 * np.sin(2 * np.pi * x / lam)), detrend="none")
    # the largest test of the same shape: L_b + 8 d = L, L_b to the nearest samples
    assert p.block_length + 8 * p.runaway_distance == pytest.approx(x[-1], abs=lam / 64 * (1 + 1e-9))


def _self_affine_rows(tmp_path):
    """A clean self-affine profile of 2000 points over 1 mm (x, z in m) from the CLI's generator."""
    p = frictal.self_affine_profile(points=2000, length=1e-3, rms_height=5e-7, seed=7)
    return np.asarray(p.x), np.asarray(p.z)


def _write(path, x, z):
    with open(path, "w") as f:
        f.write("x_m,z_m\n")
        for a, b in zip(x, z):
            f.write(f"{a!r},{b!r}\n")
    return str(path)


def test_heights_in_micrometres_labelled_metres_are_doubtful_and_z_unit_fixes_them(tmp_path):
    x, z = _self_affine_rows(tmp_path)
    clean = frictal.predict(_write(tmp_path / "clean.csv", x, z))
    assert clean.trust == "ok" and clean.trust_codes == ""
    wrong = _write(tmp_path / "wrong.csv", x, z * 1e6)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        d = frictal.predict(wrong)
    assert d.trust == "doubtful"
    assert "units-suspect" in d.trust_codes.split(",")
    assert "z_unit='um'" in d.trust_fix
    assert d.to_dict()["trust"] == "doubtful"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        fixed = frictal.predict(wrong, z_unit="um")
    assert fixed.trust == "ok"
    assert fixed.friction_angle == pytest.approx(clean.friction_angle, abs=1e-9)
    # read_surface takes the same units: x in mm labelled m, read with x_unit="mm".
    s = frictal.read_surface(_write(tmp_path / "xmm.csv", x * 1e3, z), x_unit="mm")
    assert np.allclose(s["x"], x, rtol=1e-12, atol=0)
    assert s["x_unit_scale"] == pytest.approx(1e-3)
    with pytest.raises(ValueError, match="z_unit"):
        frictal.predict(wrong, z_unit="furlong")
