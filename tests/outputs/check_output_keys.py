"""Every output key is declared: the key test of the output tables (frictal/outputs.hpp).

Runs every command that prints JSON and every Python function that returns a dict on small inputs
(files from tests/data, maps made here), walks what they print at every depth, and checks each key
against the declared tables (`frictal columns --json`): a JSON key must be declared with a unit, a
nested object's keys must be the columns of the table its unit names, a value must have the type
its unit says (an integer for "count", a flag for "flag", text for "text", numbers for units), and
a Python key must be declared as some column's Python key. The tables themselves are checked for
one unit per key and for unit suffixes that match the unit ("_deg" <-> deg, "_m" -> m, ...).

    check_output_keys.py FRICTAL_CLI PYTHON_MODULE_DIR SOURCE_DIR
"""
import json
import math
import os
import subprocess
import sys
import tempfile

CLI, MODULE_DIR, SOURCE = sys.argv[1], sys.argv[2], sys.argv[3]
sys.path.insert(0, MODULE_DIR)
import numpy as np  # noqa: E402

import frictal  # noqa: E402

failures = []


def fail(msg):
    failures.append(msg)


def cli_json(*args):
    r = subprocess.run([CLI, *args], capture_output=True, text=True, timeout=600)
    if r.returncode != 0:
        fail(f"frictal {' '.join(args)}: exit {r.returncode}: {r.stderr.strip()[:400]}")
        return None
    try:
        return json.loads(r.stdout)
    except json.JSONDecodeError as e:
        fail(f"frictal {' '.join(args)}: not JSON ({e})")
        return None


tables = {t["name"]: t for t in cli_json("columns", "--json")}
json_units = {}  # key -> {unit: [table, ...]}
python_units = {}
for t in tables.values():
    for c in t["columns"]:
        if c["key"]:
            json_units.setdefault(c["key"], {}).setdefault(c["unit"], []).append(t["name"])
        if c["python"]:
            pu = "rad" if c["unit"] == "deg" else c["unit"]
            python_units.setdefault(c["python"], {}).setdefault(pu, []).append(t["name"])

# The tables: one unit per JSON key, suffixes that say the unit.
SUFFIX = [("_m_s", "m/s"), ("_per_s", "1/s"), ("_n_per_m", "N/m"), ("_deg", "deg"), ("_kg", "kg"), ("_m2", "m2"),
          ("_pa", "Pa"), ("_n", "N"), ("_m", "m"), ("_s", "s")]
for key, units in json_units.items():
    plain = [u for u in units if not u.startswith(("object:", "list:", "rows:", "map:")) and u != "settings"]
    if len(plain) > 1:
        fail(f"JSON key {key!r} declared with {len(units)} units: {units}")
    unit = plain[0] if plain else next(iter(units))
    for suffix, u in SUFFIX:
        if key.endswith(suffix):
            if unit != u and not unit.startswith(("object:", "list:", "rows:", "map:")):
                fail(f"JSON key {key!r} ends in {suffix} but its unit is {unit!r} ({units[unit]})")
            break
    if unit == "deg" and not key.endswith("_deg"):
        fail(f"JSON key {key!r} is in degrees but does not end in _deg ({units[unit]})")
for key, units in python_units.items():
    if key.endswith("_deg"):
        fail(f"Python key {key!r} ends in _deg: Python's dicts are SI ({units})")


# One Python key rule: a column's Python key is its JSON key without the unit suffix (Python's
# values are SI, so the key does not name a unit). A column only Python has (JSON key "") names
# its own key, without a unit suffix either. Exceptions to the rule, justified (table, JSON key):
# none at present; a new one goes here with the reason.
RULE_EXCEPTIONS = set()


def without_unit(key):
    for suffix, _ in SUFFIX:
        if len(key) > len(suffix) and key.endswith(suffix):
            return key[:-len(suffix)]
    return key


# The rule itself, checked on keys written out here (not the library's function): a change to
# either side fails.
for key, want in [("theta_max_forward_deg", "theta_max_forward"), ("rms_height_m", "rms_height"),
                  ("contact_area_m2", "contact_area"), ("max_pressure_pa", "max_pressure"),
                  ("contact_stiffness_n_per_m", "contact_stiffness"), ("load_n", "load"),
                  ("speed_m_s", "speed"), ("rate_per_s", "rate"), ("mass_kg", "mass"), ("time_step_s", "time_step"),
                  ("valid_points", "valid_points"), ("m", "m"), ("_s", "_s")]:
    if without_unit(key) != want:
        fail(f"the Python key rule gives {without_unit(key)!r} for {key!r}, not {want!r}")
for t in tables.values():
    # Python-only columns may declare one key twice (a scalar or an array, by the input).
    seen = {c["python"]: "(Python only)" for c in t["columns"] if c["python"] and not c["key"]}
    for c in t["columns"]:
        if not c["python"]:
            continue
        if c["key"] and c["python"] != without_unit(c["key"]) and (t["name"], c["key"]) not in RULE_EXCEPTIONS:
            fail(f"table {t['name']}: Python key {c['python']!r} of JSON key {c['key']!r} is not the JSON key "
                 f"without its unit suffix ({without_unit(c['key'])!r})")
        if not c["key"] and without_unit(c["python"]) != c["python"]:
            fail(f"table {t['name']}: Python-only key {c['python']!r} names a unit; Python's values are SI")
        if c["key"]:
            if c["python"] in seen:
                fail(f"table {t['name']}: Python key {c['python']!r} of {c['key']!r} and {seen[c['python']]!r}")
            seen[c["python"]] = c["key"]

NUMBER_UNITS = {"deg", "rad", "m", "s", "kg", "m/s", "1/s", "1", "list", "m2", "Pa", "N", "N/m"}


def check_value(where, unit, v):
    if v is None:
        return
    if isinstance(v, (list, tuple, np.ndarray)) and unit in ("count", "flag", "text"):
        for x in v:
            check_value(where + "[]", unit, x.item() if isinstance(x, np.generic) else x)
        return
    if unit == "count":
        ok = isinstance(v, (int, np.integer)) and not isinstance(v, bool)
    elif unit == "flag":
        ok = isinstance(v, (bool, np.bool_))
    elif unit == "text":
        ok = isinstance(v, str)
    elif unit in NUMBER_UNITS:
        if isinstance(v, np.ndarray):
            ok = np.issubdtype(v.dtype, np.number)
        elif isinstance(v, (list, tuple)):
            ok = all(x is None or (isinstance(x, (int, float, np.number)) and not isinstance(x, bool))
                     or isinstance(x, (list, tuple)) for x in v)
        else:
            ok = isinstance(v, (int, float, np.number)) and not isinstance(v, bool)
    else:
        ok = True
    if not ok:
        fail(f"{where}: value {str(v)[:60]!r} is not what unit {unit!r} says")


def walk(where, obj, table_names, python):
    """Checks the keys of dict `obj` against the tables named (None: every table)."""
    units = python_units if python else json_units
    for k, v in obj.items():
        here = f"{where}.{k}"
        if table_names is None:
            declared = units.get(k)
        else:
            declared = {}
            for name in table_names:
                for c in tables[name]["columns"]:
                    ck = c["python"] if python else c["key"]
                    if ck == k:
                        u = ("rad" if c["unit"] == "deg" else c["unit"]) if python else c["unit"]
                        declared.setdefault(u, []).append(name)
        if not declared:
            fail(f"{here}: key not declared in {'any table' if table_names is None else table_names}")
            continue
        unit = next(iter(declared))
        if unit.startswith("object:"):
            if isinstance(v, dict):
                walk(here, v, [unit[7:]], python)
            elif v is not None:
                fail(f"{here}: expected an object ({unit})")
        elif unit.startswith("list:"):
            if not isinstance(v, list):
                fail(f"{here}: expected a list ({unit})")
            else:
                for i, e in enumerate(v):
                    if isinstance(e, dict):
                        walk(f"{here}[{i}]", e, [unit[5:]], python)
        elif unit.startswith("rows:"):
            # A list of rows, each the values of the table's columns in its order, each in its unit.
            # Python's dicts may hold them as a 2-D array (n rows of the table's columns).
            row_columns = tables[unit[5:]]["columns"]
            if isinstance(v, np.ndarray):
                if v.ndim != 2 or (v.size and v.shape[1] != len(row_columns)):
                    fail(f"{here}: expected an array of rows of {len(row_columns)} values ({unit})")
            elif not isinstance(v, list):
                fail(f"{here}: expected a list of rows ({unit})")
            else:
                for i, e in enumerate(v):
                    if not isinstance(e, (list, tuple)) or len(e) != len(row_columns):
                        fail(f"{here}[{i}]: expected a row of {len(row_columns)} values ({unit})")
                        continue
                    for c, x in zip(row_columns, e):
                        check_value(f"{here}[{i}].{c['key']}", c["unit"], x)
        elif unit in ("settings", "map"):
            pass  # the keys of a settings table (frictal settings; the vocabulary test) or data
        else:
            check_value(here, unit, v)


checked = []


def check_cli(table_names, *args):
    """`frictal ARGS` prints JSON whose keys are columns of the tables named (plus "command")."""
    j = cli_json(*args)
    for obj in (j if isinstance(j, list) else [j] if j is not None else []):
        walk("frictal " + " ".join(a if "/" not in a else os.path.basename(a) for a in args), obj,
             table_names + ["command"], False)
    checked.append("frictal " + args[0])


def check_py(name, d, table_names, python=True):
    """A Python dict whose keys are the Python keys of the tables named (plus "command");
    python=False: a dict with the CLI's keys (to_dict)."""
    if isinstance(d, dict):
        walk(name, d, table_names + ["command"], python)
    checked.append(name)


data = os.path.join(SOURCE, "tests", "data")
prof = os.path.join(data, "profiles", "dektak-1.csv")
prof2 = os.path.join(data, "profiles", "xy-1.txt")
tmp = tempfile.mkdtemp(prefix="frictal-keys-")


def fourier_map(n, seed, dx):
    rng = np.random.default_rng(seed)
    q = np.fft.fftfreq(n)
    qq = np.hypot(*np.meshgrid(q, q))
    qq[0, 0] = 1
    h = np.real(np.fft.ifft2(np.fft.fft2(rng.standard_normal((n, n))) * qq ** -1.8))
    return h / h.std() * 0.1 * dx * n / 20


dx = 1e-6
m1, m2 = fourier_map(48, 1, dx), fourier_map(32, 2, dx)
map1, map2 = os.path.join(tmp, "a.x3p"), os.path.join(tmp, "b.x3p")
frictal.write_x3p(map1, m1, dx=dx, dy=dx)
frictal.write_x3p(map2, m2, dx=dx, dy=dx)
koch = os.path.join(tmp, "koch.csv")
subprocess.run([CLI, "surface", "koch", "--iterations", "3", "-o", koch], check=True, capture_output=True)

# The CLI: every command that prints JSON.
check_cli(["prediction"], "predict", prof, "--json")
check_cli(["prediction"], "predict", prof, prof2, "--json", "--start-offset", "0.0003")
check_cli(["prediction"], "predict", map1, map2, "--json", "--drops", "2")
SIG = ["signature", "friction", "friction_backward", "hold", "hold_start"]
check_cli(SIG, "signature", prof, "--json")
check_cli(SIG, "signature", koch, "--json", "--start-offset", "0.001")
check_cli(["profile_stats", "profile_scan_stats", "stats_extras"], "stats", prof, "--json", "--tip-radius", "2e-6",
          "--histograms", "5")
check_cli(["map_stats", "map_grid", "map_scan_stats", "stats_extras"], "stats", map1, "--json", "--tip-radius", "2e-6")
check_cli(["dimension"], "dimension", prof, "--json")
check_cli(["koch_dimension"], "dimension", "koch", "--alpha", "60", "--method", "eq13", "--json")
check_cli(["info", "map_grid"], "info", map1, "--json")
check_cli(["info"], "info", prof, "--json")
check_cli(["areal"], "areal", map1, map2, "--json")
check_cli(["areal_hold"], "areal", map1, map2, "--lateral", "free", "--drops", "2", "--json", "-q")
check_cli(["areal_hold"], "areal", map1, map2, "--lateral", "locked", "--drops", "2", "--json", "-q")
check_cli(["areal_hold"], "areal", map1, map2, "--start-offset", "1e-5,0", "--json", "-q")
check_cli(["anisotropy"], "anisotropy", map1, "--json", "--directions", "4")
check_cli(["anisotropy"], "anisotropy", map1, "--json", "--directions", "2", "--hold", "--drops", "2",
          "--locked", "-q")
check_cli(["areal_tilt"], "areal-tilt", map1, map2, "--predict-only", "--json")
check_cli(["tilt"], "tilt", "koch", "--iterations", "2", "--json", "--max-tilt", "30", "-q")
check_cli(["warning_code"], "warnings", "--json")
check_cli(["formats"], "formats", "--json")
check_cli(["contact"], "contact", map1, "--load", "1MPa", "--modulus", "1GPa", "--poisson", "0.3", "--json")
check_cli(["contact", "contact_curve"], "contact", prof, prof, "--load", "1MPa,2MPa", "--modulus", "1GPa", "--poisson", "0.3",
          "--json")
# A study at the quick scale (seconds): its status and its findings as data; the rows' outputs are
# checked against the outputs its kind declares (frictal study kinds --json).
store = os.path.join(tmp, "fig04.sqlite")
subprocess.run([CLI, "study", "run", os.path.join(SOURCE, "studies", "fig04-koch-signature.toml"), "--store", store,
                "--quick", "--threads", "2"], check=True, capture_output=True)
check_cli(["study_status"], "study", "status", store, "--json")
check_cli(["study_report"], "study", "report", store, "--json")

# Python: every function that returns a dict (the package's wrappers add "warnings").
import warnings as _w  # noqa: E402

_w.simplefilter("ignore")
pr = frictal.read_profile(prof)
x, z = np.asarray(pr.x), np.asarray(pr.z)
check_py("read_surface", frictal.read_surface(prof), ["info"])
check_py("read_surface(map)", frictal.read_surface(map1), ["info"])
check_py("profile_stats", frictal.profile_stats(pr, tip_radius=2e-6),
         ["profile_stats", "profile_scan_stats", "stats_extras"])
check_py("signature", frictal.signature(pr, keep_contacts=True), ["signature"])
check_py("hold_angle", frictal.hold_angle(pr, runaway_distance=1e-5, start_offset=3e-4), ["hold"])
check_py("divider_dimension", frictal.divider_dimension(x, z), ["dimension"])
check_py("box_dimension", frictal.box_dimension(x, z), ["dimension"])
check_py("predict_friction", frictal.predict_friction(0.1, 0.2, 0.05), ["friction"])
check_py("predict.to_dict", frictal.predict(prof).to_dict(), ["prediction"], python=False)
check_py("predict(maps).to_dict", frictal.predict(map1, map2, drops=2).to_dict(), ["prediction"], python=False)
check_py("map_stats", frictal.map_stats(m1, dx=dx, dy=dx, tip_radius=2e-6), ["map_stats", "map_scan_stats", "stats_extras"])
check_py("anisotropy", frictal.anisotropy(m1, dx=dx, dy=dx, directions=4), ["anisotropy"])
check_py("areal_signature", frictal.areal_signature(m1, dx=dx, dy=dx, upper=m2), ["areal"])
check_py("areal_hold", frictal.areal_hold(m1, dx=dx, dy=dx, upper=m2, drops=2), ["areal_hold"])
check_py("areal_hold(start)", frictal.areal_hold(m1, dx=dx, dy=dx, upper=m2, start_offset=(1e-5, 0)), ["areal_hold"])
check_py("areal_tilt_hold", frictal.areal_tilt_hold(m1, dx=dx, dy=dx, upper=m2), ["areal_tilt_hold"])
if frictal.build_info()["mujoco"]:
    check_py("areal_tilt", frictal.areal_tilt(m1[:24, :24], dx=dx, dy=dx, upper=m2[:8, :8], runaway_distance=1e-6),
             ["areal_tilt"])
check_py("condition", frictal.condition(pr)[1], ["conditioning"])
check_py("build_info", frictal.build_info(), ["build_info"])
check_py("contact", frictal.contact(m1, spacing=dx, pressure=1e6, modulus=1e9, poisson=0.3, fields=True), ["contact"])
check_py("contact(profile)", frictal.contact(pr, load=1e3, modulus=1e9, poisson=0.3), ["contact"])
check_py("autocorrelation", frictal.autocorrelation(pr), ["autocorrelation"])
check_py("study_status", frictal.study_status(store), ["study_status"])
check_py("study_findings", frictal.study_findings([store]), ["study_report"], python=False)
kind_list = cli_json("study", "kinds", "--json")["kinds"]
kinds = {k["name"]: {o["name"] for o in k["outputs"]} for k in kind_list}
# A study output is declared once: one taken from an output table (outputs_of in study.hpp) names
# its table and column and has that column's unit (a study stores numbers only: a count or a flag
# as a unitless number) and help (after the kind's context, "context: help"); an output that the
# kind declares itself must not be named like a declared JSON key -- that would be the table's
# quantity declared a second time by hand -- unless it is listed here as another quantity under a
# name that stores and scripts/make_index.py already use.
NOT_THE_TABLES = {
    ("tilt", "friction_angle_deg"): "0, not NaN, when the block did not slide (stored values kept)",
    ("tilt", "friction_coefficient"): "tan of the simulated friction angle (the prediction table's: of the prediction)",
    ("wm-tilt", "slid"): "the run-away of 1 lambda (the run's own run-away distance is 2 lambda)",
    ("wm-tilt", "friction_angle_deg"): "read at the run-away of 1 lambda (a checkpoint of the 2 lambda run)",
    ("wm-tilt", "smallest_feature_m"): "the smaller of the two faces' (the table's: both, a list)",
    ("wm-tilt", "hold_basins"): "of the drops in the sliding direction (the table's: always forward)",
    ("wm-tilt", "points"): "points of each generated face (a curve, not a profile's statistics)",
    ("divider", "points"): "points of the Koch curve (a curve, not a profile's statistics)",
    ("wm-pair-statistics", "surface_slope_max_deg"):
        "the command table's (declared without values in the predict tier, above the study tier)",
}
table_columns = {}  # (table, key or Python key of a key-less column) -> column
for t in tables.values():
    for c in t["columns"]:
        table_columns[(t["name"], c["key"] or c["python"])] = c
from_tables = 0
for k in kind_list:
    for o in k["outputs"]:
        where = f"study kind {k['name']}: output {o['name']!r}"
        if o.get("table"):
            from_tables += 1
            c = table_columns.get((o["table"], o.get("column", "")))
            if c is None:
                fail(f"{where}: taken from column {o.get('column')!r} of table {o['table']!r}, which has none")
                continue
            unit = "1" if c["unit"] in ("count", "flag") else c["unit"]
            if o["unit"] != unit:
                fail(f"{where}: in {o['unit']!r}, its column {o['table']}.{o['column']} in {c['unit']!r}")
            if not (o["description"] == c["help"] or o["description"].endswith(": " + c["help"])):
                fail(f"{where}: its help {o['description']!r} is not its column's {c['help']!r}")
            continue
        units = json_units.get(o["name"])
        if units and (k["name"], o["name"]) not in NOT_THE_TABLES:
            fail(f"{where}: declared by hand, but {o['name']!r} is a column of {sorted(sum(units.values(), []))} "
                 f"(take it with outputs_of, or list it in NOT_THE_TABLES as another quantity)")
for (kind, name), why in NOT_THE_TABLES.items():
    outs = {o["name"]: o for k in kind_list if k["name"] == kind for o in k["outputs"]}
    if outs and (name not in outs or outs[name].get("table") or name not in json_units):
        fail(f"NOT_THE_TABLES lists {kind}.{name}, which is not a hand-declared output named like a column: drop it")
for row in frictal.study_rows(store):
    check_py("study_rows", row, ["study_row"])
    for name in list(row["scalars"]) + list(row["arrays"]):
        if name not in kinds.get(row["kind"], ()):
            fail(f"study_rows: output {name!r} of kind {row['kind']!r} is not among the kind's declared outputs")
check_py("tilt", frictal.tilt(frictal.koch_profile(iterations=2), max_tilt=0.5), ["tilt"])

print(f"checked {len(checked)} outputs: {', '.join(sorted(set(checked)))}; {from_tables} study outputs from tables")
if failures:
    print(f"{len(failures)} undeclared or mistyped keys:")
    for f in failures:
        print("  " + f)
    sys.exit(1)
print("every key declared, with its unit")
