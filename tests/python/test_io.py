"""Measured surfaces from Python: expectations from the test files' own numbers (python
zipfile/struct here), Eq. 13 and closed forms."""
import math
import os
import struct
import zipfile

import numpy as np
import pytest

import frictal

DATA = os.path.join(os.path.dirname(__file__), "..", "data")


def test_read_x3p_map_matches_zip_contents():
    path = os.path.join(DATA, "x3p", "x3p-2.x3p")
    raw = zipfile.ZipFile(path).read("bindata/data.bin")
    values = np.array(struct.unpack("<%dd" % (len(raw) // 8), raw)).reshape(650, 650)
    m = frictal.read_map(path)
    assert m["heights"].shape == (650, 650)
    assert np.array_equal(m["heights"], values)
    s = frictal.map_stats(m["heights"], dx=m["dx"], dy=m["dy"])
    assert s["Sq"] == pytest.approx(values.std(), rel=1e-12)


def test_read_surface_profile_and_warnings():
    s = frictal.read_surface(os.path.join(DATA, "profiles", "xy-2.txt"))
    assert s["kind"] == "profile"
    assert len(s["x"]) == 24
    assert any("23" in w["message"] and w["code"] == "reader" for w in s["warnings"])


def test_a_read_surface_dict_hands_its_reader_warnings_on():
    path = os.path.join(DATA, "profiles", "xy-2.txt")
    s = frictal.read_surface(path)
    with pytest.warns(frictal.FrictalWarning):
        p = frictal.predict(s).to_dict()
    # The reader's warning keeps its code and its message (the file's count line says 23 rows).
    read = [w for w in p["warnings"] if w["code"] == "reader"]
    assert len(read) == 1
    assert read[0]["message"].endswith(path + ": line 2 gives a count of 23 but 24 data rows follow; all rows were read")
    with pytest.raises(ValueError, match="'code' and 'message'"):
        frictal.predict({"x": s["x"], "z": s["z"], "warnings": ["a bare string"]})


def test_x3p_round_trip(tmp_path):
    h = np.arange(12, dtype=float).reshape(3, 4) * 1e-9
    h[1, 2] = np.nan
    p = str(tmp_path / "m.x3p")
    frictal.write_x3p(p, h, dx=1e-6, dy=2e-6, type="F")
    m = frictal.read_map(p)
    assert np.array_equal(np.isnan(m["heights"]), np.isnan(h))
    ok = ~np.isnan(h)
    assert np.array_equal(m["heights"][ok], h.astype(np.float32).astype(float)[ok])


def test_koch_dimension_and_divider():
    assert frictal.koch_dimension(math.radians(60)) == pytest.approx(math.log(4) / math.log(3), abs=1e-14)
    c = frictal.koch_curve(iterations=5, alpha=math.radians(60), wavelength=1.0, length=2.0)
    x, z = c
    fit = frictal.divider_dimension(x, z, ruler_min=3e-3, ruler_max=0.3)
    assert fit["dimension"] == pytest.approx(math.log(4) / math.log(3), abs=0.015)
    assert tuple(fit["fit_range"]) == (3e-3, 0.3)


def test_areal_signature_of_tilted_plane_and_anisotropy_of_ridges():
    x = np.arange(40) * 1e-6
    plane = np.tile(0.2 * x, (20, 1))
    r = frictal.areal_signature(plane, dx=1e-6, dy=1e-6, direction=0.0)
    assert r["theta_max_forward"] == pytest.approx(math.atan(0.2), abs=1e-12)
    ridges = np.tile(1e-7 * np.sin(x * 3e5) + 3e-8 * np.sin(x * 1.1e6), (60, 1))
    t = frictal.anisotropy(ridges, dx=1e-6, dy=1e-6, directions=4, lines=8)
    assert t["theta_forward"][1] == pytest.approx(0, abs=1e-12)  # along the ridges
    assert t["theta_forward"][0] > 0.01


def test_areal_hold_grooves_steer_when_free():
    """Grooves at 30 deg to x on a grid whose diagonal runs along them (dy = dx tan 30 deg), in
    place: the continuous model's triangulated surface is exactly grooves of one profile. Free,
    the block slides along them at the first tilt; locked to x, it holds at atan of the steepest
    face's slope, A sin(2 pi / m) / dx (bisected to 1e-4 rad)."""
    a, amp, m = 1e-7, 2e-7, 40
    dy = a * math.tan(math.pi / 6)
    i = np.arange(100)
    h = amp * np.sin(2 * math.pi * (i[None, :] - i[:, None]) / m)
    # A 6 x 6 window of the grooves as the upper face in place (the whole map nested in itself would
    # put all its 10^4 spheres in contact at once: slow).
    kw = dict(dx=a, dy=dy, upper=h[:6, :6], in_place=True, runaway_distance=1e-6, detrend="none")
    locked_angle = math.atan(amp * math.sin(2 * math.pi / m) / a)
    r = frictal.areal_hold(h, start_offset=(40 * a, 40 * dy), **kw)  # the window moved to node (40, 40)
    assert r["model"] == "map-continuous-free"
    assert r["hold_angle"] <= math.radians(0.1)
    assert r["steering"] == pytest.approx(math.pi / 6, abs=math.radians(0.5))
    # Over drops: the free closed form on every drop. The top row's block slides along the grooves
    # (D tan 30 deg towards +y) off the lower map's +y edge before it has gone D along x: nothing
    # holds it there, a run-away at the first increment as elsewhere
    # (tests/cli/test_cli_areal.cpp, CliAreal.HoldOverDropsIsThePredictionToTheDigit).
    d = frictal.areal_hold(h, drops=3, **kw)
    assert d["drop_offsets"].shape == (9, 2)
    assert max(d["drop_hold_angles"]) <= math.radians(0.1)
    locked = frictal.areal_hold(h, lateral="locked", drops=3, **kw)
    assert locked["model"] == "map-continuous-locked"
    for k in (1, 4, 7):
        assert locked_angle - 1e-9 <= locked["drop_hold_angles"][k] <= locked_angle + 2.1e-4
    with pytest.raises(ValueError, match="start offset"):
        frictal.areal_hold(h, start_offset=(1.0, 0.0), **kw)
    with pytest.raises(ValueError, match="lateral"):
        frictal.areal_hold(h, lateral="sideways", **kw)
    with pytest.raises(TypeError):
        frictal.areal_hold(h, across_max=1e-6, **kw)  # the grid lift's options are gone


def test_areal_hold_is_predict():
    """The same library path as frictal.predict: the same numbers for the same map and options."""
    rng = np.random.default_rng(3)
    h = np.cumsum(np.cumsum(rng.normal(size=(20, 24)), axis=0), axis=1) * 1e-9
    kw = dict(atomic_friction=0.05, drops=2)
    r = frictal.areal_hold(h, dx=1e-6, dy=1e-6, direction=0.5, **kw)
    p = frictal.predict(h, spacing=1e-6, direction=0.5, **kw)
    for q in ("q05", "q95", "mean", "std", "min", "max"):
        assert r["hold_angle_" + q] == getattr(p, "friction_angle_" + q), q
    assert r["hold_angle_q50"] == p.friction_angle
    assert list(r["drop_hold_angles"]) == list(p.drop_friction_angles)
    assert r["upper_bound_friction_angle"] == p.upper_bound_friction_angle
    locked = frictal.areal_hold(h, dx=1e-6, dy=1e-6, direction=0.5, lateral="locked", **kw)
    pl = frictal.predict(h, spacing=1e-6, direction=0.5, locked=True, **kw).to_dict()
    assert math.degrees(locked["hold_angle_q50"]) == pytest.approx(pl["locked_friction_angle_deg"], rel=1e-14)
    assert locked["hold_angle_free_q50"] == r["hold_angle_q50"]


def test_map_stats_scan_quantities_numpy_reference():
    """n dx sizes, per-profile Rq/Rdq and the forward-difference gradient, against numpy."""
    rng = np.random.default_rng(7)
    h = rng.normal(size=(6, 9)) * 1e-8
    dx, dy = 0.5e-6, 0.25e-6
    s = frictal.map_stats(h, dx=dx, dy=dy, tip_radius=1e-3)
    assert s["physical_size_x"] == pytest.approx(9 * dx)
    assert s["physical_size_y"] == pytest.approx(6 * dy)
    assert s["bandwidth"] == pytest.approx(((dx + dy) / 2, (9 * dx + 6 * dy) / 2))
    rows = h - h.mean(axis=1, keepdims=True)
    cols = h - h.mean(axis=0, keepdims=True)
    assert s["Rq_x"] == pytest.approx(np.sqrt((rows ** 2).mean()), rel=1e-12)
    assert s["Rq_y"] == pytest.approx(np.sqrt((cols ** 2).mean()), rel=1e-12)
    gx = np.diff(h, axis=1) / dx
    gy = np.diff(h, axis=0) / dy
    assert s["Rdq_x"] == pytest.approx(np.sqrt((gx ** 2).mean()), rel=1e-12)
    assert s["Rdq_y"] == pytest.approx(np.sqrt((gy ** 2).mean()), rel=1e-12)
    common = gx[:-1, :] ** 2 + gy[:, :-1] ** 2
    assert s["rms_gradient_fd"] == pytest.approx(np.sqrt(common.mean()), rel=1e-12)
    assert "short_reliability_cutoff" in s


def test_npy_and_single_column_are_detected(tmp_path):
    a = np.arange(12, dtype="<f4").reshape(3, 4)
    p = tmp_path / "a.npy"
    np.save(p, a)
    s = frictal.read_surface(str(p), unit="nm")
    assert s["kind"] == "map"
    assert s["format"] == "npy"
    assert s["reader"] == "native"
    one = tmp_path / "one.npy"
    np.save(one, np.array([1.0, 2.0, 4.0]))
    p1 = frictal.read_surface(str(one), spacing=0.5)
    assert p1["kind"] == "profile"
    assert np.allclose(p1["x"], [0, 0.5, 1.0])
    assert np.array_equal(s["heights"], a.astype(float) * 1e-9)
    t = tmp_path / "col.txt"
    t.write_text("# spacing: 2 um\n# unit: nm\n1\n2\n3\n")
    c = frictal.read_surface(str(t))
    assert c["kind"] == "profile"
    assert np.allclose(c["x"], [0, 2e-6, 4e-6])
    assert np.allclose(c["z"], [1e-9, 2e-9, 3e-9])


def test_profile_stats_scan_quantities_and_tip_cutoff():
    """n dx length and bandwidth of a profile; the tip cutoff of a triangle wave of slope s with
    its kinks on the samples: at a peak the stencil curvature is -2 s / h, which reaches -1/(2R)
    at h = 4 s R, a stencil length 2h = 8 s R (SurfaceTopography's definition, docs/analysis.md)."""
    dx, slope = 1e-7, 0.1
    R = 5.3 * dx / (4 * slope)
    i = np.arange(512)
    x = i * dx
    p = frictal.Profile(x, slope * dx * (16 - np.abs(i % 64 - 32)))
    s = frictal.profile_stats(p, tip_radius=R)
    assert s["sampling_interval"] == pytest.approx(dx, rel=1e-12)
    assert s["physical_length"] == pytest.approx(512 * dx, rel=1e-12)
    assert s["bandwidth"] == pytest.approx((dx, 512 * dx), rel=1e-12)
    assert s["nyquist_wavelength"] == pytest.approx(2 * dx, rel=1e-12)
    assert s["short_reliability_cutoff"] == pytest.approx(8 * slope * R, rel=1e-9)
    assert "short_reliability_cutoff" not in frictal.profile_stats(p)


def test_instrument_matrix_in_python_matches_surfacetopography():
    """matrix-4.txt.gz (gzip, Wyko ASCII header) read from Python: SurfaceTopography's
    test/IO/test_asc.py::test_example4 states 75 x 305 points, 2.773965e-05 x 0.00011280791 m,
    rms_height_from_area 1.1745891510991089e-07 m, rms_height_from_profile 7.198047e-08 m and
    rms_gradient 0.06776316911544318 (commit 119cb66, MIT)."""
    s = frictal.read_surface(os.path.join(DATA, "instruments", "matrix-4.txt.gz"))
    assert s["kind"] == "map"
    h = s["heights"]
    assert h.shape == (305, 75)
    assert 75 * s["dx"] == pytest.approx(2.773965e-05, rel=1e-6)
    assert 305 * s["dy"] == pytest.approx(0.00011280791, rel=1e-6)
    st = frictal.map_stats(h, dx=s["dx"], dy=s["dy"])
    assert st["Sq"] == pytest.approx(1.1745891510991089e-07, rel=1e-6)
    assert st["Rq_x"] == pytest.approx(7.198047e-08, rel=1e-6)
    assert st["rms_gradient_fd"] == pytest.approx(0.06776316911544318, rel=1e-6)


def test_gwyddion_backed_instrument_file_with_a_channel():
    """nid-1.nid (Nanosurf, read through Gwyddion's ezdfile module) from Python, by channel name:
    SurfaceTopography's test/IO/test_ezd.py::test_ezd_metadata states 256 x 256 points, 2e-5 m and
    rms height 3.026701737129839e-07 m for 'Scan forward (Z-AxisSensor)' (commit 119cb66, MIT)."""
    path = os.path.join(DATA, "instruments", "nid-1.nid")
    try:
        s = frictal.read_surface(path, channel="Z-AxisSensor forward")
    except Exception as e:  # built or installed without Gwyddion
        if "gwyddion" in str(e).lower():
            pytest.skip(str(e))
        raise
    assert s["reader"] == "gwyddion:ezdfile"
    h = s["heights"]
    assert h.shape == (256, 256)
    assert 256 * s["dx"] == pytest.approx(2e-5, rel=1e-6)
    assert frictal.map_stats(h, dx=s["dx"], dy=s["dy"])["Sq"] == pytest.approx(3.026701737129839e-07, rel=1e-6)
    assert np.sqrt(((h - h.mean()) ** 2).mean()) == pytest.approx(3.026701737129839e-07, rel=1e-6)


def _surfacetopography_cutoff(z, px, radius, safety=0.5):
    """SurfaceTopography's scanning_probe_reliability_cutoff for a uniform line scan, written
    here from its definition (Generic/ScanningProbe.py, Uniform/Derivative.py at commit 119cb66):
    second derivative at stencil length `distance` = 2 s px from linearly interpolated heights at
    x +- s px, kept where the stencil lies inside the scan; the distance where its minimum reaches
    -safety/radius, bracketed by 2 px .. n px / 2 (here by bisection instead of Brent)."""
    n = len(z)
    x = np.arange(n, dtype=float)

    def objective(distance):
        s = distance / (2 * px)
        d = (np.interp(x - s, x, z) - 2 * z + np.interp(x + s, x, z)) / (s * px) ** 2
        d = d[int(np.ceil(s)):n - int(np.ceil(s))]
        return safety / radius + (d.min() if len(d) else 0.0)

    a, b = 2 * px, n * px / 2
    if objective(a) > 0:
        return 0.0
    if objective(b) < 0:
        return float("nan")
    for _ in range(200):
        m = 0.5 * (a + b)
        a, b = (m, b) if objective(m) < 0 else (a, m)
    return 0.5 * (a + b)


def test_tip_cutoff_equals_surfacetopography_definition_on_a_random_profile():
    """A second method for short_reliability_cutoff: the definition re-implemented in numpy on a
    rough random profile (smoothed random walk), for tip radii from sharper than every peak to
    blunt."""
    rng = np.random.default_rng(1)
    n, px = 2000, 1e-8
    z = np.convolve(np.cumsum(rng.normal(size=n)) * 1e-9, np.ones(5) / 5, mode="same")
    p = frictal.Profile(np.arange(n) * px, z)
    for radius in (1e-8, 1e-7, 1e-6, 1e-5):
        want = _surfacetopography_cutoff(z, px, radius)
        got = frictal.profile_stats(p, tip_radius=radius)["short_reliability_cutoff"]
        assert got == pytest.approx(want, rel=1e-9, abs=1e-20), radius


def test_areal_tilt_grooves_across_on_mujoco():
    """The 3D tilt test (MuJoCo) on sinusoidal grooves across the sliding direction, an 8 x 8
    window of the same grooves in place: free and locked both hold until the steepest chord of the
    triangulated grooves, atan(A sin(2 pi / m) / dx) (closed form), from every seat (so the
    prediction's spread is that angle too); the simulation reads the first 0.1 deg increment at or
    above it. The keywords are the settings table's."""
    if not frictal.build_info()["mujoco"]:
        pytest.skip("built without MuJoCo")
    a, m, n = 1e-6, 10, 30
    amp = 0.3642 * a * m / (2 * math.pi)
    i = np.arange(n)
    h = np.tile(amp * np.sin(2 * math.pi * i / m), (n, 1))
    expected = math.degrees(math.atan(amp * math.sin(2 * math.pi / m) / a))
    r = frictal.areal_tilt(h, dx=a, dy=a, upper=h[11:19, 11:19], turn_over_upper=False,
                           start_offset=(11 * a, 11 * a), runaway_distance=1e-6)
    assert r["ran_away"]
    assert math.degrees(r["predicted_hold_angle"]) == pytest.approx(expected, abs=0.01)
    # Grooves across d: the locked block (a diagnostic, as `frictal areal-tilt`) holds to the same face.
    assert math.degrees(r["predicted_hold_angle_locked"]) == pytest.approx(expected, abs=0.01)
    # Every seat in a groove across d holds to the same face: the spread is that one angle.
    lo, hi = r["continuous_hold_angle_range"]
    assert math.degrees(lo) == pytest.approx(expected, abs=0.01)
    assert math.degrees(hi) == pytest.approx(expected, abs=0.01)
    assert expected - 0.01 <= math.degrees(r["friction_angle"]) <= expected + 0.1 + 0.01
    # One row per increment (tilt, x, y, rested, steps, force, speed): the last one, at the friction
    # angle, did not come to rest (the block ran away).
    trace = r["increment_trace"]
    assert len(trace) > 0 and all(len(row) == 7 for row in trace)
    assert trace[-1][0] == r["friction_angle"] and trace[-1][3] is False
    names = {f["name"] for f in frictal.areal_tilt_settings()}
    assert {"local_damping", "lateral", "collision", "mujoco_time_step"} <= names
    with pytest.raises(TypeError, match="did you mean 'local_damping'"):
        frictal.areal_tilt(h, dx=a, dy=a, local_dampng=0.5)
    with pytest.raises(ValueError, match="local_damping"):
        frictal.areal_tilt(h, dx=a, dy=a, local_damping=1.5)


def test_areal_tilt_hold_without_mujoco_on_grooves():
    """The matched prediction alone (no MuJoCo): sinusoidal grooves across the sliding direction
    with an 8 x 8 window of them in place hold to the steepest chord of the triangulated grooves,
    atan(A sin(2 pi / m) / dx) (closed form), from every seat (no spread); put down at 10 deg it
    holds to the same face; with atomic friction to that face's angle plus atan(mu_a) (Eq. 6)."""
    a, m, n = 1e-6, 10, 30
    amp = 0.3642 * a * m / (2 * math.pi)
    h = np.tile(amp * np.sin(2 * math.pi * np.arange(n) / m), (n, 1))
    expected = math.degrees(math.atan(amp * math.sin(2 * math.pi / m) / a))
    for start_tilt in (0.0, math.radians(10)):
        r = frictal.areal_tilt_hold(h, dx=a, dy=a, upper=h[11:19, 11:19], turn_over_upper=False,
                                    start_offset=(11 * a, 11 * a), start_tilt=start_tilt, runaway_distance=1e-6)
        assert r["ran_away"]
        assert expected - 1e-6 <= math.degrees(r["hold_angle"]) <= expected + math.degrees(2e-4)
        lo, hi = r["hold_angle_range"]
        assert math.degrees(lo) == pytest.approx(expected, abs=0.01)
        assert math.degrees(hi) == pytest.approx(expected, abs=0.01)
        assert len(r["stop_tilt"]) == len(r["stop_x"]) > 0
    # With atomic friction the face holds to atan(slope) + atan(mu_a) (Eq. 6); a negative one is refused.
    r = frictal.areal_tilt_hold(h, dx=a, dy=a, upper=h[11:19, 11:19], turn_over_upper=False,
                                start_offset=(11 * a, 11 * a), runaway_distance=1e-6, atomic_friction=0.1,
                                spread=False)
    with_mu = expected + math.degrees(math.atan(0.1))
    assert with_mu - 1e-4 <= math.degrees(r["hold_angle"]) <= with_mu + math.degrees(2e-4)
    assert "hold_angle_range" not in r
    with pytest.raises(ValueError, match="atomic_friction"):
        frictal.areal_tilt_hold(h, dx=a, dy=a, atomic_friction=-0.1)
