"""Studies from Python: the same library functions as `frictal study ...` (study_bindings.cpp)."""
import math
import pathlib
import tomllib

import pytest

import frictal

ROOT = pathlib.Path(__file__).resolve().parents[2]

STUDY = """
[study]
name = "py-koch"
seed = 1
[[part]]
name = "theory"
kind = "koch-signature"
[part.parameters]
iterations = [0, 1, 2]
alpha = 10.0
length = 0.01
"""


def test_kinds_list_outputs_and_views():
    kinds = {k["name"]: k for k in frictal.study_kinds()}
    assert {"koch-signature", "wm-pair-statistics", "tilt", "divider", "wm-tilt"} <= set(kinds)
    for k in kinds.values():
        assert k["available"] or k["name"] == "areal-tilt"  # areal-tilt needs MuJoCo
        names = {o["name"] for o in k["outputs"]}
        for v in k["plots"]:
            assert v["y"]["column"] in names
    units = {o["name"]: o["unit"] for o in kinds["koch-signature"]["outputs"]}
    assert units["friction_angle_deg"] == "deg"


def test_every_figure_view_of_the_study_files_is_declared_by_a_kind_of_its_parts():
    kinds = {k["name"]: k for k in frictal.study_kinds()}
    for path in sorted((ROOT / "studies").glob("*.toml")):
        study = tomllib.loads(path.read_text(encoding="utf-8"))
        declared = {v["id"] for p in study["part"] for v in kinds[p["kind"]]["plots"]}
        for fig in study.get("figure", []):
            for panel in fig.get("panel", [fig]):
                for view in panel["views"]:
                    assert view in declared, f"{path.name}: figure {fig['file']}: view {view}"


def test_run_status_rows_report_export(tmp_path):
    toml = tmp_path / "koch.toml"
    toml.write_text(STUDY, encoding="utf-8")
    store = str(tmp_path / "koch.sqlite")
    s = frictal.study_run(str(toml), store, threads=2)
    assert s["ran"] == 3 and s["failed"] == 0 and s["tasks"]["done"] == 3
    assert frictal.study_run(str(toml), store)["ran"] == 0  # resumed: nothing left
    st = frictal.study_status(store)
    assert st["study"] == "py-koch" and st["tasks"]["done"] == 3
    assert st["parts"][0]["kind"] == "koch-signature" and st["parts"][0]["available"]
    rows = frictal.study_rows(store, "theory")
    # Sec. III: theta_max = 1, 1, 2 alpha for K0, K1, K2.
    ratios = {r["params"]["iterations"]: r["scalars"]["theta_max_over_alpha"] for r in rows}
    assert ratios == pytest.approx({0: 1.0, 1: 1.0, 2: 2.0}, abs=1e-9)
    assert len(rows[0]["arrays"]["signature_theta_over_alpha"]) == len(rows[0]["arrays"]["signature_offset_over_wavelength"])
    rep = frictal.study_report(store)
    assert "[SUPPORTED]" in rep and "1, 1, 2, 3 times alpha" in rep
    # The same findings as data: the Koch maxima (theta_max/alpha = 1, 1, 2 checked above, exact)
    # are the koch-theta-max claim, supported on this part, one conclusion per claim.
    fj = frictal.study_findings([store])
    koch = [f for r in fj["reports"] for f in r["findings"] if f["claim_id"] == "koch-theta-max"]
    assert koch and all(f["verdict"] == "supported" and f["part"] == "theory" for f in koch)
    ids = [c["id"] for c in fj["conclusions"]]
    assert len(ids) == len(set(ids)) and "koch-theta-max" in ids
    files = frictal.study_export(store, str(tmp_path / "csv"))
    assert files[0] == "tasks.csv" and "theory.csv" in files and files[-1] == "report.md"
    wide = (tmp_path / "csv" / "theory.csv").read_text().splitlines()
    assert wide[0].startswith("task_id,alpha,iterations,length,")
    assert len(wide) == 4
    phi = float(wide[3].split(",")[wide[0].split(",").index("friction_angle_deg")])
    assert math.isclose(phi, 20.0, abs_tol=1e-9)  # K2 at alpha = 10 deg: phi = 2 alpha


def test_run_many_gives_the_stores_of_separate_runs(tmp_path):
    other = STUDY.replace('name = "py-koch"', 'name = "py-koch-b"').replace("[0, 1, 2]", "[1, 2, 3]")
    (tmp_path / "a.toml").write_text(STUDY)
    (tmp_path / "b.toml").write_text(other)
    sep = tmp_path / "separate"
    sep.mkdir()
    for name in ("a", "b"):
        frictal.study_run(str(tmp_path / f"{name}.toml"), str(sep / f"{name}.sqlite"), cache="none")
    one = tmp_path / "one"
    one.mkdir()
    sums = frictal.study_run_many([str(tmp_path / "a.toml"), str(tmp_path / "b.toml")], str(one), threads=2)
    assert [s["study"] for s in sums] == ["py-koch", "py-koch-b"]
    # K1 and K2 at alpha = 10 deg are in both: computed once, reused in the other study.
    assert sum(s["ran"] for s in sums) == 4
    assert sum(s["reused"] for s in sums) == 2
    for name in ("a", "b"):
        got = frictal.study_rows(str(one / f"{name}.sqlite"), arrays=False)
        want = frictal.study_rows(str(sep / f"{name}.sqlite"), arrays=False)
        assert got == want


def test_errors():
    with pytest.raises(OSError, match="no such store file"):
        frictal.study_status("/nonexistent/frictal.sqlite")
    with pytest.raises(OSError, match="cannot open the study file"):
        frictal.study_run("/nonexistent/study.toml", "/tmp/never.sqlite")
