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
