"""frictal.predict under load (docs/load.md): the keywords, the keys, and the errors naming them."""
import math
import os
import warnings

import pytest

import frictal

DATA = os.path.join(os.path.dirname(__file__), "..", "data", "profiles")


def quiet(f, *args, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return f(*args, **kw)


def test_a_load_gives_the_curve_and_no_load_the_rigid_answer():
    path = os.path.join(DATA, "xy-1.txt")
    rigid = quiet(frictal.predict, path)
    assert rigid.to_dict()["load_n"] is None and rigid.load_curve == []
    p = quiet(frictal.predict, path, load=1e-6, modulus=70e9, poisson=0.3, upper_modulus="rigid")
    assert p.model == "profile-hertz-asperity-hold"
    assert p.load == 1e-6
    assert len(p.load_curve) == 7 and p.load_curve[4] == 1e-6  # W x 10^(-2..1) in half decades
    assert p.load_curve_median[4] == p.friction_angle
    assert p.rigid_friction_angle == rigid.friction_angle
    assert p.contact_modulus == pytest.approx(70e9 / (1 - 0.3**2))
    assert math.isfinite(p.load_approach) and p.load_approach > 0


def test_errors_name_the_keyword():
    path = os.path.join(DATA, "xy-1.txt")
    with pytest.raises(ValueError, match="modulus= .*poisson="):
        frictal.predict(path, load=1e-3)
    with pytest.raises(ValueError, match="give load="):
        frictal.predict(path, modulus=70e9, poisson=0.3)
    with pytest.raises(ValueError, match="upper_modulus"):
        frictal.predict(path, load=1e-3, modulus=70e9, poisson=0.3, upper_modulus="steel")
