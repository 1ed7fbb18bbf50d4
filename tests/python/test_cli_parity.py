"""Python = CLI: the same file and options give the same numbers in Python as in the CLI's --json.

Each case runs the CLI (FRICTAL_CLI, else `frictal` on PATH; skipped where neither exists) and
the Python function on the same measured profiles from tests/data, once on the path and once on
the Profile that read_profile returns (the one conditioning rule applies to both), and compares
every number the two print. The CLI is the second computation: a different front end, its own
option parsing and reading, its own JSON writer.
"""
import json
import math
import os
import shutil
import subprocess
import warnings

import numpy as np
import pytest

import frictal

DATA = os.path.join(os.path.dirname(__file__), "..", "data", "profiles")
CLI = os.environ.get("FRICTAL_CLI") or shutil.which("frictal")
pytestmark = pytest.mark.skipif(CLI is None, reason="no frictal CLI (set FRICTAL_CLI)")

# Measured profiles of three instruments/formats: a Dektak scan, a text x,z pair, a non-uniform scan.
FILES = ["dektak-1.csv", "xy-1.txt", "nonuniform.asc"]
# Options as the CLI spells them, and as Python's keywords do.
OPTIONS = [
    ([], {}),
    (["--detrend", "none"], {"detrend": "none"}),
    (["--detrend", "poly:2", "--atomic-friction", "0.1"], {"detrend": "poly:2", "atomic_friction": 0.1}),
]
# Every file with every option set, but the Dektak scan with its form kept (its tilt makes the
# lift long: 9 s a run, and nothing the other two files do not test).
CASES = [(f, *o) for f in FILES for o in OPTIONS if not (f == "dektak-1.csv" and o[1].get("detrend") == "none")]
# Friction under load (predict only): the load (N; a list, the first the headline) and the material.
LOAD_CASES = [("xy-1.txt", ["--load", "1e-6N,1e-5N", "--modulus", "70GPa", "--poisson", "0.3"],
               {"load": [1e-6, 1e-5], "modulus": 70e9, "poisson": 0.3})]


def cli(*args):
    r = subprocess.run([CLI, *args, "--json"], capture_output=True, text=True, timeout=120, check=True)
    return json.loads(r.stdout)


def quiet(f, *args, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return f(*args, **kw)


def deg(v):
    return None if v is None else math.degrees(v)


def same(a, b):
    """Equal numbers (to the last few bits: the CLI's JSON writes 17 digits) or both null."""
    if a is None or b is None:
        return a is None and b is None
    return a == pytest.approx(b, rel=1e-12, abs=1e-15)


def inputs(name):
    path = os.path.join(DATA, name)
    return [path, frictal.read_profile(path)]


@pytest.mark.parametrize("name,cli_opts,py_opts", CASES + LOAD_CASES)
def test_predict_equals_the_cli(name, cli_opts, py_opts):
    want = cli("predict", os.path.join(DATA, name), *cli_opts)
    for surface in inputs(name):
        got = quiet(frictal.predict, surface, **py_opts).to_dict()
        json.dumps(got, allow_nan=False)  # JSON-safe: None where the CLI writes null
        assert set(got) == set(want) - {"lower", "upper"}
        for key, value in want.items():
            if key in ("lower", "upper", "warnings"):
                continue
            if isinstance(value, float) or isinstance(got[key], float):
                assert same(got[key], value), (key, got[key], value)
            else:
                assert got[key] == value, key
        # The readers' notes come with a path (a Profile object carries none).
        codes = [w["code"] for w in want["warnings"] if isinstance(surface, str) or w["code"] != "reader"]
        assert [w["code"] for w in got["warnings"]] == codes


@pytest.mark.parametrize("name,cli_opts,py_opts", CASES)
def test_signature_and_hold_angle_equal_the_cli(name, cli_opts, py_opts):
    want = cli("signature", os.path.join(DATA, name), *cli_opts)
    mu_a = py_opts.get("atomic_friction", 0.0)
    sig_opts = {k: v for k, v in py_opts.items() if k != "atomic_friction"}
    for surface in inputs(name):
        s = quiet(frictal.signature, surface, **sig_opts)
        assert s["conditioning"] == want["conditioning"]
        for key in ("theta_max_forward", "theta_max_backward", "contact_slope_mean", "contact_slope_std"):
            assert same(deg(s[key]), want[key + "_deg"]), key
        assert same(s["offset_at_forward"], want["offset_at_forward_m"])
        assert len(s["offset"]) == want["offsets"] and s["exact"] == want["exact"]
        # The plausibility codes of the conditioned profile and the bounds' (the readers' notes
        # aside: a Profile object carries none).
        # Python's signature() has no atomic friction: its bounds are theta_max alone, and so are
        # their codes only without one.
        if mu_a == 0:
            codes = {w["code"] for w in s["warnings"]} - {"reader"}
            assert codes == {w["code"] for w in want["warnings"]} - {"reader"}

        h = quiet(frictal.hold_angle, surface, atomic_friction=mu_a, **sig_opts)
        assert h["conditioning"] == want["conditioning"]
        assert same(h["runaway_distance"], want["runaway_distance_m"])
        for side, suffix in (("forward", ""), ("backward", "_backward")):
            for kind in ("hold_angle", "inertial_hold_angle"):
                for stat in ("mean", "std", "q05", "q50", "q95", "min", "max"):
                    key = f"{kind}{suffix}_{stat}_deg"
                    assert same(deg(h[side][kind][stat]), want[key]), key


def test_numpy_heights_are_conditioned_by_the_same_rule(tmp_path):
    # The Dektak scan's heights as a 1-D array with a spacing, and the same heights written on that
    # grid as a file for the CLI (x_m,z_m): the same conditioning (a line) and the same numbers.
    z = np.asarray(frictal.read_profile(os.path.join(DATA, "dektak-1.csv")).z)[:4000]
    dx = 2e-7
    path = tmp_path / "grid.csv"
    np.savetxt(path, np.column_stack([np.arange(len(z)) * dx, z]), delimiter=",", header="x_m,z_m", comments="",
               fmt="%.17g")
    want = cli("predict", str(path))
    got = quiet(frictal.predict, z, spacing=dx).to_dict()
    assert got["conditioning"] == want["conditioning"] == "form: line"
    for key in ("friction_angle_deg", "friction_angle_q05_deg", "friction_angle_q95_deg", "theta_max_deg"):
        assert got[key] == pytest.approx(want[key], rel=1e-9), key
    s = quiet(frictal.signature, z, spacing=dx)
    assert math.degrees(s["theta_max_forward"]) == pytest.approx(want["theta_max_deg"], rel=1e-9)


def test_a_missing_file_is_file_not_found_with_its_path():
    missing = os.path.join(DATA, "no-such-scan.csv")
    for f in (frictal.read_profile, frictal.read_surface, frictal.read_map, frictal.predict, frictal.signature,
              frictal.hold_angle):
        with pytest.raises(FileNotFoundError) as e:
            f(missing)
        assert e.value.filename == missing
    r = subprocess.run([CLI, "predict", missing], capture_output=True, text=True, timeout=60)
    assert r.returncode != 0 and missing in r.stderr


def test_tilt_of_a_measured_profile_equals_the_cli():
    # A 50 um piece of the Dektak scan: Python conditions it (a line) and scales the defaults to it
    # by the library call the CLI makes; the same run, bit for bit.
    path = os.path.join(DATA, "dektak-1.csv")
    want = cli("tilt", "--lower", path, "--crop", "0.5mm,0.55mm", "--quiet")
    piece, _ = frictal.condition(frictal.read_profile(path), crop=(5e-4, 5.5e-4), detrend="none")
    got = quiet(frictal.tilt, piece)
    assert got["surface"]["conditioning"] == "form: line"
    # Both load a measured pair as the library's setup says: quasi-statically, the rotation held.
    assert got["protocol"] == want["protocol"] == "quasi-static"
    assert got["scaled_defaults"]["measured_defaults"] == want["scaled_defaults"]["measured_defaults"]
    assert got["scaled_defaults"]["measured_defaults"] == "protocol = quasi-static, hold_rotation = true"
    assert got["validity"] == want["validity"] and got["friction_angle_valid"] == want["friction_angle_valid"]
    assert same(deg(got["friction_angle"]), want["friction_angle_deg"])
    assert got["steps"] == want["steps"]
    scaled = {t["name"]: (t["from"], t["to"]) for t in got["scaled_defaults"]["settings"]}
    assert set(scaled) == {t["name"] for t in want["scaled_defaults"]["settings"]}
    assert same(scaled["normal_stiffness"][1], want["settings"]["normal_stiffness"])
    # The nested objects the CLI prints come from the same tables: the cost estimate, key for key
    # (Python's key: the JSON key without its unit suffix; no angle to convert), and the stages timed.
    def py_key(k):
        return k[:-2] if k.endswith(("_s", "_m")) else k

    assert set(got["estimate"]) == {py_key(k) for k in want["estimate"]}
    assert all(same(got["estimate"][py_key(k)], v) for k, v in want["estimate"].items())
    assert got["stage_time"].keys() == want["stage_time_s"].keys()


def test_tilt_dict_is_the_cli_s_json_key_for_key(tmp_path):
    """tilt() of a measured Profile and `frictal tilt --json` of its file: every key the CLI prints
    is in Python's dict under its Python key (`frictal columns`), with the same value in SI (the
    JSON's degrees converted here from the unit the table declares); the settings and surface
    objects key for key (a setting's JSON value in its text unit, deg for an angle: tilt_settings()
    names its SI unit). Both run the test that predict() states: the same block, d and drops."""
    # A 0.3 mm piece of the Dektak scan, written out for the CLI (the same points, the conditioning
    # of both front ends a line on it).
    piece, _ = frictal.condition(frictal.read_profile(os.path.join(DATA, "dektak-1.csv")), crop=(5e-4, 8e-4),
                                 detrend="none")
    path = str(tmp_path / "piece.csv")
    frictal.write_profile_csv(path, piece)
    # The CLI writes the series (as Python returns it) so that its series_interval is Python's.
    want = cli("tilt", "--lower", path, "--quiet", "-o", str(tmp_path / "series.csv"))
    got = quiet(frictal.tilt, piece)
    tables = {t["name"]: t["columns"] for t in cli("columns")}
    setting_unit = {f["name"]: f["unit"] for f in frictal.tilt_settings()}
    timings = {"wall_time_s", "setup_time_s", "us_per_step", "stage_time_s"}  # this run's wall clock

    def si(unit, v):
        return math.radians(v) if unit in ("deg", "rad") and isinstance(v, (int, float)) and v is not None else v

    def equal(unit, cli_value, py_value):
        if isinstance(cli_value, list):
            return len(cli_value) == len(py_value) and all(equal(unit, c, p) for c, p in zip(cli_value, py_value))
        if isinstance(cli_value, (bool, str)) or cli_value is None:
            return cli_value == py_value or (cli_value is None and (py_value is None or py_value != py_value))
        return same(float(py_value), si(unit, cli_value))

    def compare(table, cli_obj, py_obj, where):
        columns = {c["key"]: c for c in tables[table]}
        n = 0
        for key, value in cli_obj.items():
            if key in timings or key in ("lower", "upper"):  # the wall clock; the files the CLI read
                continue
            if key == "warnings":  # the same codes and words; the CLI names the file, Python "lower"
                assert [(w["code"], w["message"].replace(path, "lower")) for w in value] == [
                    (w["code"], w["message"]) for w in py_obj["warnings"]]
                n += 1
                continue
            c = columns[key]
            assert c["python"] in py_obj, (where, key)
            v = py_obj[c["python"]]
            if c["unit"].startswith("object:"):
                n += compare(c["unit"][7:], value, v, f"{where}.{key}")
            elif c["unit"].startswith("list:"):
                assert len(value) == len(v), (where, key)
                for i, (a, b) in enumerate(zip(value, v)):
                    if c["unit"] == "list:tilt_scaled_setting":  # from/to in the setting's unit
                        assert a["name"] == b["name"]
                        u = setting_unit[a["name"]]
                        assert same(b["from"], si(u, a["from"])) and same(b["to"], si(u, a["to"])), (a, b)
                    else:
                        n += compare(c["unit"][5:], a, b, f"{where}.{key}[{i}]")
            elif key == "settings":
                assert set(value) == set(v), (set(value) ^ set(v))
                for k, x in value.items():
                    assert equal(setting_unit[k], x, v[k]), (k, x, v[k])
                n += len(value)
            elif key == "surface":
                n += compare("tilt_surface", value, v, "surface")
            else:
                assert equal(c["unit"], value, v), (where, key, value, v)
                n += 1
        return n

    assert compare("tilt", want, got, "tilt") >= 100
    # Python's dict holds nothing beyond the CLI's keys but its own (series, steps_beyond_limit).
    py_keys = {c["python"] for c in tables["tilt"] if c["key"] in want}
    assert set(got) - py_keys <= {"series", "steps_beyond_limit"}, set(got) - py_keys
    assert set(got["surface"]) == {c["python"] for c in tables["tilt_surface"] if c["key"] in want["surface"]} - {""}
    # The test is predict()'s: its block, d and drop range.
    p = quiet(frictal.predict, piece)
    assert got["surface"]["block_length"] == pytest.approx(p.block_length, rel=1e-15)
    assert got["surface"]["runaway_distance"] == pytest.approx(p.runaway_distance, rel=1e-15)
    assert got["surface"]["drop_range"] == pytest.approx(tuple(p.drop_range), rel=1e-15)
    assert got["surface"]["test_lengths"] == p.test_lengths
    assert got["predicted_spread_median"] == pytest.approx(p.friction_angle, rel=1e-12)


def test_study_status_equals_the_cli(tmp_path):
    """A store's status from Python and from `frictal study status --json`: the same keys and values,
    the per-version counts (objects keyed by version) included."""
    toml = tmp_path / "koch.toml"
    toml.write_text('[study]\nname = "parity"\nseed = 1\n[[part]]\nname = "theory"\nkind = "koch-signature"\n'
                    '[part.parameters]\niterations = [0, 1]\nalpha = 10.0\nlength = 0.01\n', encoding="utf-8")
    store = str(tmp_path / "koch.sqlite")
    assert frictal.study_run(str(toml), store, threads=1)["tasks"] == {"total": 2, "done": 2, "failed": 0, "pending": 0}
    want = cli("study", "status", store)
    got = frictal.study_status(store)
    assert got.keys() == want.keys()
    for k in want:
        if k != "parts":
            assert got[k] == want[k], k
    assert len(got["parts"]) == len(want["parts"]) == 1
    assert got["parts"][0] == want["parts"][0]
    assert got["parts"][0]["done_by_frictal_version"] == {frictal.__version__: 2}


def test_the_bound_warnings_are_the_librarys_words(tmp_path):
    # A ramp descending along +x under a flat block: every contact slope is -0.1, so the rigid
    # bound theta_max is below zero (bound-negative), in `frictal areal` and in Python's
    # areal_signature with the same words: one library check, not one per front end.
    n, dx = 24, 1e-6
    ramp = np.tile(-0.1 * np.arange(n) * dx, (n, 1))
    flat = np.zeros((8, 8))
    lo, up = str(tmp_path / "ramp.x3p"), str(tmp_path / "flat.x3p")
    frictal.write_x3p(lo, ramp, dx=dx, dy=dx)
    frictal.write_x3p(up, flat, dx=dx, dy=dx)
    c = cli("areal", lo, up, "--detrend", "none")
    p = quiet(frictal.areal_signature, ramp, dx=dx, dy=dx, upper=flat)
    assert p["theta_max_forward"] == pytest.approx(math.atan(-0.1), abs=1e-9)

    def bound(ws):
        return [(w["code"], w["message"]) for w in ws if w["code"] == "bound-negative"]

    assert len(bound(c["warnings"])) == 1
    assert bound(p["warnings"]) == bound(c["warnings"])


def test_a_map_pair_under_load_equals_the_cli(tmp_path):
    """Friction under load for maps (the half-space, docs/load.md "Maps"): crossed waves, 24 x 24
    nodes, against themselves turned over, 2 x 2 drops."""
    x = np.arange(24)
    z = 2e-7 * np.sin(0.6 * x)[None, :] * np.cos(0.45 * x)[:, None] + 1e-8 * (x % 3)[None, :]
    path = str(tmp_path / "waves.x3p")
    frictal.write_x3p(path, z, dx=1e-6, dy=1e-6)
    want = cli("predict", path, "--drops", "2", "--load", "1mN", "--modulus", "70GPa", "--poisson", "0.3")
    got = quiet(frictal.predict, path, drops=2, load=1e-3, modulus=70e9, poisson=0.3).to_dict()
    assert got["model"] == want["model"] == "map-halfspace-locked-hold"
    for key, value in want.items():
        if key in ("lower", "upper", "warnings") or key not in got:
            continue
        if isinstance(value, float) or isinstance(got[key], float):
            assert same(got[key], value), (key, got[key], value)
        else:
            assert got[key] == value, key


def test_the_cli_s_tilt_frames_read_back_in_python(tmp_path):
    """`frictal tilt --frames` written by the CLI, read by frictal.read_tilt_frames: the last frame's
    upper centroid has moved down the slope by the displacement the CLI's JSON reports (the block
    slides along the lower block's surface: the distance between the centroids' start and end,
    seen in the lower block's frame)."""
    frames = tmp_path / "k0.txt"
    j = cli("tilt", "koch", "--iterations", "0", "--alpha", "10", "--max-tilt", "16", "--frames", str(frames),
            "--frame-interval", "0.02")
    f = frictal.read_tilt_frames(str(frames))
    n = len(f["time"])
    assert n >= 5 and f["position"].shape == (n, 2, 2) and f["angle"].shape == (n, 2)
    assert f["lower_polygon"].shape[1] == 2 and f["upper_polygon"].shape[1] == 2
    assert np.all(np.diff(f["time"]) > 0)
    # Frames carry the tilt in radians; the run slid at the friction angle, so the last frames are
    # beyond it and the first below it.
    phi = math.radians(j["friction_angle_deg"])
    assert f["tilt"][0] < phi <= f["tilt"][-1] + 1e-9
    with pytest.raises(FileNotFoundError):
        frictal.read_tilt_frames(str(tmp_path / "missing.txt"))
    bad = tmp_path / "bad.txt"
    bad.write_text("frictal-dem-frames 1\nbody 0 lower 3\n0 0\n1 x\n0 1\n")
    with pytest.raises(ValueError, match="line 4"):
        frictal.read_tilt_frames(str(bad))


def test_settings_tables_are_the_clis():
    """predict_settings(), conditioning_settings(), signature_settings(), areal_signature_settings(),
    anisotropy_settings(), tilt_settings(), areal_tilt_settings() and generators() list the fields that `frictal settings
    --json` lists, with the same name, option, type and help; Python's unit is the SI unit that
    the CLI names si_unit, and its default the CLI's in SI (degrees in the CLI, radians here)."""
    cli = json.loads(subprocess.run([CLI, "settings", "--json"], check=True, capture_output=True, text=True).stdout)
    pairs = [(cli["tilt"], frictal.tilt_settings()), (cli["areal_tilt"], frictal.areal_tilt_settings())]
    pairs += [(cli["predict"], frictal.predict_settings()), (cli["conditioning"], frictal.conditioning_settings())]
    pairs += [(cli["signature"], frictal.signature_settings()), (cli["areal"], frictal.areal_signature_settings()),
              (cli["anisotropy"], frictal.anisotropy_settings())]
    pairs += [(cli["generators"][name]["fields"], fields) for name, fields in frictal.generators().items()]
    assert len(pairs) > 4
    for c_fields, p_fields in pairs:
        assert [f["name"] for f in c_fields] == [f["name"] for f in p_fields]
        for c, p in zip(c_fields, p_fields):
            for k in ("name", "option", "type", "help"):
                assert c[k] == p[k], (c["name"], k)
            assert c["si_unit"] == p["unit"], c["name"]
            if c["type"] == "boolean":
                assert c["default"] == ("true" if p["default"] else "false"), c["name"]
            elif c["type"] == "word" and p["default"] is None:
                assert c["default"] not in p["choices"], c["name"]  # automatic: said in words
            elif c["type"] == "word":
                assert c["default"] == p["default"] and p["default"] in p["choices"], c["name"]
            elif c["type"] == "integer":
                assert isinstance(p["default"], int) and float(c["default"]) == p["default"], c["name"]
            elif p["default"] is None:
                assert not c["default"][:1].isdigit(), c["name"]  # automatic: a word, not a number
            else:
                try:
                    text = float(c["default"])
                except ValueError:  # a default the surface or the command sets, said in words
                    continue
                factor = 180 / math.pi if c["unit"] == "deg" else 1.0
                assert text == pytest.approx(p["default"] * factor, rel=1e-5), c["name"]


def test_areal_tilt_equals_the_cli(tmp_path):
    """The 3D tilt test (MuJoCo) in Python and in the CLI on the same maps (written to X3P for the
    CLI): every key `frictal areal-tilt --json` prints is in Python's dict without its unit suffix,
    with the same value in SI (the degrees of the JSON, and of its rows' angle columns, converted
    here from the unit that `frictal columns` declares)."""
    if not frictal.build_info()["mujoco"]:
        pytest.skip("built without MuJoCo")
    a, m, n = 1e-6, 10, 30
    amp = 0.3642 * a * m / (2 * math.pi)
    h = np.tile(amp * np.sin(2 * math.pi * np.arange(n) / m), (n, 1))
    lower, upper = str(tmp_path / "lower.x3p"), str(tmp_path / "upper.x3p")
    frictal.write_x3p(lower, h, dx=a, dy=a)
    frictal.write_x3p(upper, h[11:19, 11:19], dx=a, dy=a)
    want = cli("areal-tilt", lower, upper, "--in-place", "--start-offset", "11e-6,11e-6", "--runaway-distance", "1e-6",
               "--detrend", "none", "--quiet")
    got = frictal.areal_tilt(h, dx=a, dy=a, upper=h[11:19, 11:19], turn_over_upper=False, start_offset=(11 * a, 11 * a),
                             runaway_distance=1e-6)
    tables = {t["name"]: t["columns"] for t in cli("columns")}
    columns = {c["key"]: c for c in tables["areal_tilt"]}

    def si(unit, v):
        return math.radians(v) if unit == "deg" and v is not None else v

    def equal(unit, cli_value, py_value):
        if isinstance(cli_value, list):
            return len(cli_value) == len(py_value) and all(equal(unit, c, p) for c, p in zip(cli_value, py_value))
        if isinstance(cli_value, (bool, str)) or cli_value is None:
            return cli_value == py_value or (cli_value is None and py_value != py_value)  # null: NaN
        return same(float(py_value), si(unit, cli_value))

    compared = 0
    for key, value in want.items():
        if key in ("lower", "upper", "conditioning", "seconds"):
            continue  # the files the CLI read, and its wall time
        if key == "warnings":
            assert got["warnings"] == value
            continue
        c = columns[key]
        assert c["python"] in got, key
        if c["unit"].startswith("rows:"):
            units = [r["unit"] for r in tables[c["unit"][5:]]]
            rows = got[c["python"]]
            assert len(rows) == len(value) > 0, key
            for cli_row, py_row in zip(value, rows):
                assert all(equal(u, x, y) for u, x, y in zip(units, cli_row, py_row)), (key, cli_row, py_row)
        else:
            assert equal(c["unit"], value, got[c["python"]]), (key, value, got[c["python"]])
        compared += 1
    assert compared >= 25
    # Python's dict holds nothing beyond the CLI's keys but its own wall time.
    assert set(got) - {columns[k]["python"] for k in want if k in columns} <= {"seconds", "warnings"}
