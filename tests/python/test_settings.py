"""Keywords derived from the library's settings tables, docstrings, and the GIL released around
long calls."""
import inspect
import math
import threading
import time

import numpy as np
import pytest

import frictal


def test_generator_keywords_are_the_table_names():
    tables = frictal.generators()
    assert list(tables) == ["koch", "wm", "sawtooth", "sine", "self-affine", "fourier"]
    koch = {f["name"]: f for f in tables["koch"]}
    assert list(koch) == ["iterations", "alpha", "wavelength", "length"]
    assert koch["alpha"]["unit"] == "rad"
    assert koch["alpha"]["default"] == pytest.approx(math.radians(5))
    assert "rise_angle" in {f["name"] for f in tables["sawtooth"]}
    # Every name is accepted by the generator's function and by surface(); nothing else is.
    for gen, fields in tables.items():
        fn = getattr(frictal, gen.replace("-", "_") + "_profile")
        defaults = {f["name"]: f["default"] for f in fields}
        p = fn(**defaults)
        q = frictal.surface(gen, **defaults)
        np.testing.assert_array_equal(p.z, q.z)
        with pytest.raises(TypeError, match="unexpected keyword argument 'bogus'"):
            fn(bogus=1)
    with pytest.raises(TypeError, match="did you mean 'alpha'"):
        frictal.koch_profile(alhpa=0.1)
    with pytest.raises(ValueError, match="unknown surface generator 'kosh'.*did you mean 'koch'"):
        frictal.surface("kosh")


def test_generated_surfaces_match_their_definitions():
    # Sawtooth of rise angle 30 deg over half a wavelength: top = 0.5 lambda tan(30 deg).
    s = frictal.surface("sawtooth", rise_angle=math.radians(30), wavelength=0.01, length=0.02)
    assert max(s.z) == pytest.approx(0.005 * math.tan(math.radians(30)), rel=1e-12)
    assert s.period == pytest.approx(0.01)
    x, z = frictal.surface_curve("koch", iterations=1, alpha=math.radians(50), length=0.01)
    assert np.any(np.diff(x) < 0)  # K1 folds over above 45 deg
    with pytest.raises(ValueError, match="alpha"):
        frictal.koch_profile(alpha=math.radians(70))


def test_fourier_profile_has_its_rms_period_and_spectrum():
    # Fixed amplitudes: every periodogram value is the target C0 (q / q_r)^-(1 + 2H) exactly; the
    # ratio between two wavenumbers above the rolloff is (k2 / k1)^-(1 + 2H) (numpy's FFT).
    p = frictal.fourier_profile(points=512, length=1e-3, hurst=0.6, rolloff_wavelength=1e-4,
                                short_cutoff_wavelength=1e-5, rms_height=1e-6, amplitudes="fixed", seed=4)
    assert len(p) == 513 and p.period == pytest.approx(1e-3)
    assert p.z[0] == p.z[-1]
    assert frictal.profile_stats(p)["rms_height"] == pytest.approx(1e-6, rel=1e-12)
    P = np.abs(np.fft.rfft(p.z[:-1])) ** 2
    assert P[40] / P[20] == pytest.approx(2.0 ** -2.2, rel=1e-9)
    assert P[5] == pytest.approx(P[9], rel=1e-9)  # flat below the rolloff (k = 10)
    assert P[101:].max() < 1e-20 * P[1]  # nothing above the cutoff (k = 100)
    with pytest.raises(ValueError, match="Nyquist"):
        frictal.fourier_profile(points=64, length=1e-3, short_cutoff_wavelength=2e-5, rolloff_wavelength=1e-4)
    with pytest.raises(ValueError, match="amplitudes"):
        frictal.fourier_profile(amplitudes="uniform")


def test_tilt_keywords_are_the_table_names():
    table = frictal.tilt_settings()
    names = [f["name"] for f in table]
    for expected in ("atomic_friction", "normal_stiffness", "spheroradius", "block_height", "time_step", "max_tilt", "face"):
        assert expected in names
    assert len(set(names)) == len(names)
    by = {f["name"]: f for f in table}
    assert by["max_tilt"]["unit"] == "rad"
    assert by["max_tilt"]["default"] == pytest.approx(math.radians(89))
    assert by["initial_offset"]["default"] is None
    doc = frictal.tilt.__doc__
    for n in names:
        assert f"    {n}" in doc, n
    # Every keyword is read: a value outside the field's range is refused naming it.
    flat = frictal.Profile([0.0, 0.2], [0.0, 0.0])
    for f in table:
        if f["type"] in ("number", "integer") and math.isfinite(f["min"]):
            bad = f["min"] - 1
        elif f["type"] == "word":
            bad = "bogus"
        else:
            continue
        with pytest.raises(ValueError, match=f["name"]):
            frictal.tilt(flat, **{f["name"]: bad})
    with pytest.raises(TypeError, match="did you mean 'time_step'"):
        frictal.tilt(frictal.koch_profile(), time_stp=1e-5)
    with pytest.raises(ValueError, match="face"):
        frictal.tilt(frictal.koch_profile(), face="bogus")
    with pytest.raises(ValueError, match="max_tilt"):
        frictal.tilt(frictal.koch_profile(), max_tilt=2.0)


def test_public_functions_have_docstrings_with_units():
    for name in frictal.__all__:
        obj = getattr(frictal, name)
        if not callable(obj) or inspect.isclass(obj) or inspect.ismodule(obj):
            continue
        doc = obj.__doc__ or ""
        assert len(doc.splitlines()) >= 2 and len(doc) > 80, name
        units = ("m", "rad", "metres", "radians", "unitless", "SI", "deg")
        assert any(u in doc.replace("(", " ").replace(")", " ").replace(",", " ").split() for u in units), name


def test_two_signatures_in_two_threads_run_without_the_gil():
    f = frictal.self_affine_profile(points=200000, seed=1)
    g = frictal.self_affine_profile(points=200000, seed=2)
    intervals = {}
    ticks = []
    done = threading.Event()

    def work(k):
        t0 = time.perf_counter()
        frictal.signature(f, g, threads=1, offsets=60000)
        intervals[k] = (t0, time.perf_counter())

    threads = [threading.Thread(target=work, args=(k,)) for k in range(2)]
    for t in threads:
        t.start()
    # The main thread keeps running Python while the two computations run: it could not if a
    # signature call held the GIL.
    while any(t.is_alive() for t in threads):
        ticks.append(time.perf_counter())
        time.sleep(0.002)
    for t in threads:
        t.join()
    (a0, a1), (b0, b1) = intervals[0], intervals[1]
    # The two calls overlap in time.
    assert max(a0, b0) < min(a1, b1)
    # Python ran in the middle of the overlap: the GIL was released during both calls.
    lo, hi = max(a0, b0), min(a1, b1)
    mid = [t for t in ticks if lo + 0.25 * (hi - lo) < t < hi - 0.25 * (hi - lo)]
    assert len(mid) >= 2, (intervals, len(ticks))


def test_predict_keywords_are_the_table_names():
    """predict() takes the fields of predict_settings() and conditioning_settings() under their names,
    each with its meaning in the docstring, and besides them only the stated keywords that are no
    setting of the prediction (the reading of the inputs, the one drop, friction under load, threads)."""
    table = frictal.predict_settings() + frictal.conditioning_settings()
    names = [f["name"] for f in table]
    assert names[:3] == ["direction", "atomic_friction", "runaway_distance"]
    assert {"block_length", "drops", "locked", "in_place", "crop", "remove_spikes", "spike_threshold", "detrend"} <= set(names)
    assert len(set(names)) == len(names)
    by = {f["name"]: f for f in table}
    assert by["direction"]["unit"] == "rad" and by["runaway_distance"]["unit"] == "m"
    assert by["runaway_distance"]["default"] is None and by["detrend"]["default"] is None  # automatic
    assert by["drops"]["default"] == 5 and by["spike_threshold"]["default"] == 10
    assert by["detrend"]["choices"] == ["none", "mean", "line", "plane", "poly:N"]
    doc = frictal._core.predict.__doc__
    for n in names:
        assert f"    {n}" in doc, n
    extras = ["spacing", "format", "unit", "x_unit", "z_unit", "start_offset", "threads", "load", "modulus",
              "poisson", "upper_modulus", "upper_poisson"]
    for n in extras:
        assert n in doc, n
    # Every field is accepted at its default (None: automatic) and gives the prediction without it.
    z = 1e-4 * np.sin(np.linspace(0, 40, 801))
    base = quiet_predict(z, spacing=1e-5).to_dict()
    for f in table:
        assert quiet_predict(z, spacing=1e-5, **{f["name"]: f["default"]}).to_dict() == base, f["name"]
    # Every keyword is read: a value outside the field's range is refused naming it and the range.
    for f in table:
        if f["type"] in ("number", "integer") and math.isfinite(f["min"]):
            bad, says = f["min"] - 1, f["name"] + ": expected"
        elif f["type"] == "word":
            bad, says = "bogus", f["name"]
        elif f["type"] == "number":
            bad, says = float("nan"), f["name"] + ": expected a finite number"
        else:
            continue
        with pytest.raises(ValueError, match=says):
            quiet_predict(z, spacing=1e-5, **{f["name"]: bad})
    with pytest.raises(ValueError, match=r"drops: expected a whole number in 2\.\.64, got 1"):
        quiet_predict(z, spacing=1e-5, drops=1)
    with pytest.raises(ValueError, match="block_length: expected a number > 0 m or whole, got -1"):
        quiet_predict(z, spacing=1e-5, block_length=-1)
    with pytest.raises(TypeError, match="did you mean 'runaway_distance'"):
        quiet_predict(z, spacing=1e-5, runaway_distanse=1e-3)
    # A stated value reaches the prediction (the block's length, in metres, or the whole profile).
    assert quiet_predict(z, spacing=1e-5, detrend="none", block_length=2e-3).block_length == pytest.approx(2e-3)
    whole = quiet_predict(z, spacing=1e-5, detrend="none", block_length="whole")
    assert whole.block_length == pytest.approx(8e-3)


def quiet_predict(*args, **kw):
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return frictal.predict(*args, **kw)


def test_conditioning_keywords_are_the_table_names():
    """condition(), signature() and hold_angle() take the conditioning under the fields of
    conditioning_settings(), each line of the table in their docstrings; a stated crop keeps the
    points of the window (counted here with numpy), the defaults change nothing, a value outside a
    field's range is refused naming it, and a misspelt keyword names the nearest one."""
    table = frictal.conditioning_settings()
    assert [f["name"] for f in table] == ["crop", "remove_spikes", "spike_threshold", "detrend"]
    x = np.linspace(0, 4e-3, 401)
    z = 1e-5 * np.sin(2 * math.pi * x / 7e-4) + 3e-6 * np.cos(2 * math.pi * x / 3e-4)
    prof = {"x": x, "z": z}
    for fn in (frictal.condition, frictal.signature, frictal.hold_angle, frictal._core.contact):
        for f in table:
            assert f"    {f['name']}" in fn.__doc__, (fn.__name__, f["name"])
    # condition(): the window's points, in metres as a sequence or as the table's text.
    inside = int(np.count_nonzero((x >= 1e-3 - 1e-12) & (x <= 3e-3 + 1e-12)))
    seq, rec = frictal.condition(prof, crop=(1e-3, 3e-3), detrend="none")
    txt, _ = frictal.condition(prof, crop="1e-3,3e-3", detrend="none")
    assert len(seq.x) == inside == len(txt.x) and rec["cropped"]
    np.testing.assert_array_equal(seq.z, z[(x >= 1e-3 - 1e-12) & (x <= 3e-3 + 1e-12)])
    plain, _ = frictal.condition(prof)
    defaults, _ = frictal.condition(prof, **{f["name"]: f["default"] for f in table})
    np.testing.assert_array_equal(plain.z, defaults.z)
    # signature() and hold_angle(): the same conditioning (a sequence or text crop), defaults change nothing.
    for fn, key in ((frictal.signature, "theta_max_forward"), (frictal.hold_angle, "runaway_distance")):
        a = fn(prof, **{f["name"]: f["default"] for f in table})
        b = fn(prof)
        assert a[key] == b[key] and a["conditioning"] == b["conditioning"], fn.__name__
        c1, c2 = fn(prof, crop=(1e-3, 3e-3)), fn(prof, crop="1e-3,3e-3")
        assert c1[key] == c2[key] and c1[key] != b[key], fn.__name__
        with pytest.raises(ValueError, match="spike_threshold: expected"):
            fn(prof, spike_threshold=-1)
        with pytest.raises(ValueError, match="detrend"):
            fn(prof, detrend="bogus")
        with pytest.raises(TypeError, match=f"{fn.__name__}\\(\\) got an unexpected keyword argument 'detrnd'; "
                           "did you mean 'detrend'"):
            fn(prof, detrnd="none")
    with pytest.raises(TypeError, match="did you mean 'offsets'"):
        frictal.signature(prof, ofsets=10)
    with pytest.raises(TypeError, match="did you mean 'remove_spikes'"):
        frictal.condition(prof, remove_spike=True)
    with pytest.raises(TypeError, match="did you mean 'spike_threshold'"):
        frictal.contact(prof, load=1.0, modulus=1e9, poisson=0.3, spike_treshold=5)
    with pytest.raises(ValueError, match="detrend"):
        frictal.contact(prof, load=1.0, modulus=1e9, poisson=0.3, detrend="bogus")


def test_areal_hold_keywords_are_the_table_names():
    """areal_hold() takes predict()'s fields that apply to maps under their names (the old angle
    and turn_over_upper name their new ones), and each reaches the prediction as predict()'s."""
    names = {f["name"] for f in frictal.predict_settings() + frictal.conditioning_settings()}
    doc = frictal.areal_hold.__doc__
    taken = names - {"locked", "block_length", "period"}
    for n in taken:
        assert f"    {n}" in doc, n
    rng = np.random.default_rng(5)
    h = np.cumsum(np.cumsum(rng.normal(size=(16, 18)), axis=0), axis=1) * 1e-9
    with pytest.raises(TypeError, match="'angle'; it is now 'direction'"):
        frictal.areal_hold(h, dx=1e-6, dy=1e-6, angle=0.5)
    with pytest.raises(TypeError, match="'turn_over_upper'; it is now 'in_place"):
        frictal.areal_hold(h, dx=1e-6, dy=1e-6, turn_over_upper=False)
    with pytest.raises(TypeError, match="did you mean 'lateral'"):
        frictal.areal_hold(h, dx=1e-6, dy=1e-6, laterl="free")
    with pytest.raises(TypeError, match="unexpected keyword argument 'locked'"):
        frictal.areal_hold(h, dx=1e-6, dy=1e-6, locked=True)  # lateral= says it
    kw = dict(direction=1.0, atomic_friction=0.1, drops=2, runaway_distance=1e-6, crop=(2e-6, 15e-6, 1e-6, 14e-6),
              detrend="mean")
    r = frictal.areal_hold(h, dx=1e-6, dy=1e-6, **kw)
    p = quiet_predict(h, spacing=1e-6, **kw)
    assert r["direction"] == 1.0 and r["atomic_friction"] == 0.1 and r["runaway_distance"] == 1e-6
    assert r["drops"] == 4 and len(r["drop_hold_angles"]) == 4  # a 2 x 2 grid
    assert list(r["drop_hold_angles"]) == list(p.drop_friction_angles)
    assert r["conditioning"] == p.conditioning


def _refused(fn, f, **kw):
    """A value outside field f's range given to fn is refused, naming the field (ValueError)."""
    if f["type"] in ("number", "integer") and math.isfinite(f["min"]):
        bad, says = f["min"] - 1, f["name"] + ": expected"
    elif f["type"] == "word":
        bad, says = "bogus", f["name"]
    elif f["type"] == "number":
        bad, says = float("nan"), f["name"] + ": expected a finite number"
    else:
        return False
    with pytest.raises(ValueError, match=says):
        fn(**kw, **{f["name"]: bad})
    return True


def test_signature_keywords_are_the_table_names():
    """signature() takes the fields of signature_settings() under their names (each line of the
    table in its docstring); the defaults change nothing, every keyword is read (a value outside
    its range is refused naming it), and a stated value reaches the signature: offset_range as a
    pair of metres or as the table's text, offsets N as N equal offsets over it."""
    table = frictal.signature_settings()
    names = [f["name"] for f in table]
    assert names == ["slopes", "offsets", "keep_grid", "exact", "offset_range", "bins", "spheroradius"]
    by = {f["name"]: f for f in table}
    assert by["offset_range"]["unit"] == "m" and by["offset_range"]["default"] is None  # automatic
    assert by["bins"]["default"] == 90 and by["spheroradius"]["default"] is None and by["slopes"]["default"] == "exact"
    assert by["spheroradius"] == {**{f["name"]: f for f in frictal.tilt_settings()}["spheroradius"], "default": None}
    for n in names:
        assert f"    {n}" in frictal.signature.__doc__, n
    k = frictal.koch_profile(iterations=2, alpha=np.radians(20))
    base = frictal.signature(k)
    with_defaults = frictal.signature(k, **{f["name"]: f["default"] for f in table})
    for key in ("theta_max_forward", "theta_max_backward", "offset"):
        np.testing.assert_array_equal(with_defaults[key], base[key])
    refused = [f["name"] for f in table if _refused(lambda **kw: frictal.signature(k, **kw), f)]
    assert refused == ["slopes", "offsets", "offset_range", "bins", "spheroradius"]
    with pytest.raises(ValueError, match=r"bins: expected a whole number in 1\.\.100000, got 0"):
        frictal.signature(k, bins=0)
    with pytest.raises(ValueError, match="offset_range '2 1': expected MIN MAX"):
        frictal.signature(k, offset_range=(2.0, 1.0))
    with pytest.raises(TypeError, match="offset_range: expected"):
        frictal.signature(k, offset_range=(0.0, 1.0, 2.0))
    with pytest.raises(TypeError, match="did you mean 'keep_grid'"):
        frictal.signature(k, keep_gird=True)
    # offsets=N over offset_range: N equal offsets from MIN to MAX (ends included), the same with the text.
    length = k.x[-1] - k.x[0]
    pair = frictal.signature(k, offsets=11, offset_range=(0.1 * length, 0.3 * length))
    text = frictal.signature(k, offsets=11, offset_range=f"{0.1 * length!r},{0.3 * length!r}")
    np.testing.assert_allclose(pair["offset"], np.linspace(0.1 * length, 0.3 * length, 11), rtol=0, atol=1e-15)
    np.testing.assert_array_equal(pair["theta"], text["theta"])
    # bins: the contact-slope PDF's bins.
    assert len(frictal.signature(k, bins=7)["contact_slope_pdf"]["density"]) == 7


def test_areal_signature_and_anisotropy_keywords_are_the_table_names():
    """areal_signature() takes areal_signature_settings() and anisotropy() anisotropy_settings()
    under their names (the old angle, turn_over_upper and max_lines name the new ones); the
    direction and in_place are the prediction's fields; anisotropy(areal=True) is, per direction,
    areal_signature() of the map against itself at that direction."""
    a_names = [f["name"] for f in frictal.areal_signature_settings()]
    assert a_names == ["direction", "atomic_friction", "step", "max_offset", "contact_slope", "in_place"]
    p_by = {f["name"]: f for f in frictal.predict_settings()}
    for f in frictal.areal_signature_settings():
        if f["name"] in ("direction", "in_place", "atomic_friction"):
            assert f["help"] == p_by[f["name"]]["help"], f["name"]
    an_names = [f["name"] for f in frictal.anisotropy_settings()]
    assert an_names == ["directions", "lines", "atomic_friction", "areal", "contact_slope"]
    for fn, table in ((frictal.areal_signature, frictal.areal_signature_settings()),
                      (frictal.anisotropy, frictal.anisotropy_settings())):
        for f in table:
            assert f"    {f['name']}" in fn.__doc__, (fn.__name__, f["name"])
    rng = np.random.default_rng(3)
    h = np.cumsum(np.cumsum(rng.normal(size=(40, 42)), axis=0), axis=1) * 1e-9
    grid = dict(dx=1e-6, dy=1e-6)
    with pytest.raises(TypeError, match="'angle'; it is now 'direction'"):
        frictal.areal_signature(h, angle=0.5, **grid)
    with pytest.raises(TypeError, match="'turn_over_upper'; it is now 'in_place"):
        frictal.areal_signature(h, turn_over_upper=False, **grid)
    with pytest.raises(TypeError, match="'max_lines'; it is now 'lines'"):
        frictal.anisotropy(h, max_lines=8, **grid)
    with pytest.raises(ValueError, match="contact_slope: .*needs areal=True"):
        frictal.anisotropy(h, contact_slope="mean", **grid)
    for fn, table in ((frictal.areal_signature, frictal.areal_signature_settings()),
                      (frictal.anisotropy, frictal.anisotropy_settings())):
        for f in table:
            _refused(lambda **kw: fn(h, **grid, **kw), f)
    with pytest.raises(ValueError, match=r"directions: expected a whole number in 1\.\.3600, got 0"):
        frictal.anisotropy(h, directions=0, **grid)
    with pytest.raises(ValueError, match="step: expected a number > 0 m, got 0"):
        frictal.areal_signature(h, step=0.0, **grid)
    # Stated values reach the signature: step and max_offset set the offsets 0, step, ... max_offset.
    r = frictal.areal_signature(h, direction=0.0, step=2e-6, max_offset=8e-6, **grid)
    np.testing.assert_allclose(r["offset"], [0, 2e-6, 4e-6, 6e-6, 8e-6], rtol=0, atol=1e-18)
    # anisotropy(areal=True): per direction k the areal signature at 2 pi k / directions.
    t = frictal.anisotropy(h, directions=4, areal=True, contact_slope="mean", atomic_friction=0.2, **grid)
    for k in range(4):
        s = frictal.areal_signature(h, direction=2 * math.pi * k / 4, contact_slope="mean", **grid)
        assert t["theta_forward"][k] == s["theta_max_forward"] and t["sigma"][k] == s["contact_slope_std"]
        assert t["upper_bound_friction_angle"][k] == pytest.approx(s["theta_max_forward"] + math.atan(0.2))
    lines = frictal.anisotropy(h, directions=4, lines=4, **grid)
    assert lines["direction"][1] == pytest.approx(math.pi / 2)
