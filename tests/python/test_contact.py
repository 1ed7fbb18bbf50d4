"""frictal.contact: elastic normal contact against Hertz (a sphere on a map, a cylinder in plane
strain), a load curve against separate solves, the CLI's numbers, and its warnings issued through
warnings.warn."""
import json
import math
import os
import shutil
import subprocess
import tempfile

import numpy as np
import pytest

import frictal


def sphere(n=160, dx=1e-6, R=0.01):
    x = (np.arange(n) - n // 2) * dx
    X, Y = np.meshgrid(x, x)
    return -(X ** 2 + Y ** 2) / (2 * R)


def test_hertz_sphere_contact_radius_peak_pressure_and_stiffness():
    # a = (3 F R / (4 E*))^(1/3), p0 = 3 F / (2 pi a^2), dF/d(delta) = 2 E* a, delta = a^2 / R.
    E, nu, R, a = 3e9, 0.4, 0.01, 32e-6
    Es = E / (1 - nu ** 2)
    F = 4 * Es * a ** 3 / (3 * R)
    r = frictal.contact(sphere(R=R), spacing=1e-6, load=F, modulus=E, poisson=nu, detrend="none", fields=True)
    assert math.sqrt(r["contact_area"] / math.pi) == pytest.approx(a, rel=0.01)
    assert r["max_pressure"] == pytest.approx(3 * F / (2 * math.pi * a * a), rel=0.01)
    assert r["contact_stiffness"] == pytest.approx(2 * Es * a, rel=0.02)
    assert r["approach"] == pytest.approx(a * a / R, rel=0.01)
    assert r["pressure"].shape == (160, 160)
    assert r["pressure"].sum() * 1e-12 == pytest.approx(F, rel=1e-9)
    assert r["gap"][r["pressure"] > 0].max() == pytest.approx(0, abs=1e-6 * a * a / R)


def test_hertz_cylinder_plane_strain():
    # a = sqrt(4 F' R / (pi E*)), p0 = 2 F' / (pi a); F' per unit depth.
    E, nu, R, dx = 1e9, 0.3, 0.02, 1e-6
    Es = E / (1 - nu ** 2)
    a = 300 * dx
    Fp = math.pi * Es * a * a / (4 * R)
    x = (np.arange(2048) - 1024) * dx
    r = frictal.contact(-x ** 2 / (2 * R), spacing=dx, load=Fp, modulus=E, poisson=nu, detrend="none")
    assert r["contact_length"] / 2 == pytest.approx(a, rel=0.01)
    assert r["max_pressure"] == pytest.approx(2 * Fp / (math.pi * a), rel=0.01)
    assert r["contact_area"] is None or math.isnan(r["contact_area"])


def test_curve_matches_separate_solves_and_the_cli():
    h = sphere(64, 1e-6)
    loads = [1e5, 1e6, 4e6]
    curve = frictal.contact(h, spacing=1e-6, pressure=loads, modulus=1e9, poisson=0.3, detrend="none",
                            periodic=True)
    assert isinstance(curve, list) and len(curve) == 3
    for p, c in zip(loads, curve):
        one = frictal.contact(h, spacing=1e-6, pressure=p, modulus=1e9, poisson=0.3, detrend="none", periodic=True)
        assert c["contact_area_fraction"] == pytest.approx(one["contact_area_fraction"], abs=1e-12)
        assert c["mean_separation"] == pytest.approx(one["mean_separation"], rel=1e-5)
    cli = os.environ.get("FRICTAL_CLI") or shutil.which("frictal")
    if not cli:
        pytest.skip("no frictal CLI on PATH")
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "sphere.x3p")
        frictal.write_x3p(path, h, dx=1e-6, dy=1e-6)
        out = subprocess.run([cli, "contact", path, "--load", "1e5Pa,1MPa,4MPa", "--modulus", "1GPa", "--poisson",
                              "0.3", "--detrend", "none", "--periodic", "--json"], capture_output=True, text=True,
                             check=True).stdout
    for c, j in zip(curve, json.loads(out)["curve"]):
        for key in ("contact_area_fraction", "max_pressure_pa", "mean_separation_m", "contact_stiffness_n_per_m"):
            # Python's key: the JSON key without its unit suffix
            py_key = key.removesuffix("_pa").removesuffix("_n_per_m").removesuffix("_m")
            assert j[key] == pytest.approx(c[py_key], rel=1e-9), key


def test_warnings_and_errors():
    # A wave of rms slope 2 pi D / L / sqrt(2) = 0.44: beyond the small-slope approximation.
    x = np.arange(256) * 1e-4 / 256
    steep = 1e-5 * np.cos(2 * np.pi * x / 1e-4)
    with pytest.warns(frictal.FrictalWarning, match="small-slope"):
        r = frictal.contact(steep, spacing=1e-4 / 256, pressure=1e6, modulus=1e9, poisson=0.3, detrend="none",
                            periodic=True)
    assert any(w["code"] == "small-slope" for w in r["warnings"])
    with pytest.raises(ValueError, match="Poisson's ratio"):
        frictal.contact(steep, spacing=1e-6, pressure=1e6, modulus=1e9, poisson=0.6)
    with pytest.raises(ValueError, match="load"):
        frictal.contact(steep, spacing=1e-6, pressure=-1.0, modulus=1e9, poisson=0.3)
    with pytest.raises(ValueError, match="one of them"):
        frictal.contact(steep, spacing=1e-6, modulus=1e9, poisson=0.3)
