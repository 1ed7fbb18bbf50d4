"""frictal — static friction between rigid rough surfaces from their topography.

Thin Python layer over the C++ library (``frictal._core``). SI units everywhere: metres and
radians (use ``numpy.degrees`` for display). Errors from the library raise ``ValueError`` with a
message naming the parameter or file.

>>> import frictal, numpy as np
>>> k2 = frictal.koch_profile(iterations=2, alpha=np.radians(20))
>>> sig = frictal.signature(k2)
>>> round(np.degrees(sig["theta_max_forward"]), 6)
40.0
"""
from ._core import (  # noqa: F401
    Profile,
    fourier_profile,
    generators,
    hold_angle,
    koch_curve,
    koch_profile,
    lift_direct,
    lower_envelope,
    predict_friction,
    profile_stats,
    read_profile,
    rotate180,
    sawtooth_profile,
    self_affine_profile,
    signature,
    sine_profile,
    surface,
    surface_curve,
    upper_envelope,
    wm_profile,
    write_profile_csv,
)

from ._core import (  # noqa: F401  measured surfaces (io_bindings.cpp)
    anisotropy,
    areal_hold,
    areal_signature,
    autocorrelation,
    box_dimension,
    condition,
    detrend,
    divider_dimension,
    koch_dimension,
    map_stats,
    power_spectrum,
    psd_dimension,
    read_map,
    read_surface,
    write_x3p,
)

from ._core import tilt, tilt_settings  # noqa: F401  spheropolygon tilting-block test (dem_bindings.cpp)
from ._core import areal_tilt, areal_tilt_hold, areal_tilt_settings  # noqa: F401  3D tilt test (dem_bindings.cpp)
from ._core import __version__, build_info  # noqa: F401  version defined once, in CMakeLists.txt

from ._core import (  # noqa: F401  studies: run a study file, read its store (study_bindings.cpp)
    study_export,
    study_kinds,
    study_report,
    study_rows,
    study_run,
    study_run_many,
    study_status,
)

from ._core import Prediction, prediction_columns, warning_codes  # noqa: F401  the prediction (predict_bindings.cpp)


class FrictalWarning(UserWarning):
    """Base class of frictal's warnings: a number computed without error that a reader should not
    trust as it stands. ``code`` is the library's warning code (``frictal.warning_codes()``)."""

    code = ""


def _category_name(code):
    return "".join(part.capitalize() for part in code.split("-")) + "Warning"


#: One warnings category per library code, e.g. ``frictal.UnitsSuspectWarning`` for "units-suspect",
#: so that ``warnings.filterwarnings("error", category=frictal.SpikesWarning)`` selects one code.
WARNING_CATEGORIES = {
    _code: type(_category_name(_code), (FrictalWarning,), {"code": _code, "__doc__": _meaning})
    for _code, _meaning in warning_codes().items()
}
globals().update({cls.__name__: cls for cls in WARNING_CATEGORIES.values()})


def predict(lower, upper=None, **options):
    """What a tilt test of two surfaces reads: the same prediction as ``frictal predict``.

    ``lower`` and ``upper`` (default: ``lower`` itself, turned over) are file paths, ``Profile``
    objects, dicts from ``read_surface``/``read_map``, or numpy arrays of heights (1-D: a profile,
    2-D: a map with rows along y) with ``spacing=`` in metres. Options (SI: radians, metres):
    ``direction`` (profiles: 0 or pi), ``atomic_friction``, ``runaway_distance`` (0: the default),
    ``detrend`` ("none", "mean", "line", "plane", "poly:N"; default line for profiles, plane for
    maps), ``crop`` ((x0, x1) or (x0, x1, y0, y1) in m: keep that window of each surface first),
    ``remove_spikes`` (replace, for maps mask, the points more than ``spike_threshold`` rms heights
    from the median of their neighbours, after the crop and before the form; default 10),
    ``start_offset`` (x, or (x, y) for maps: one drop), ``drops`` (maps: N x N), ``locked``
    (maps: the locked diagnostic), ``format``, ``unit``, ``threads``.

    Returns a ``Prediction``: SI attributes (``friction_angle`` is the median over drops of the hold
    angle, atomic friction included; ``upper_bound_friction_angle`` is theta_max + theta_a) and
    ``to_dict()`` with the keys and units of ``frictal predict --json``. Each of its warnings is also
    issued through ``warnings.warn`` with the category of its code (``FrictalWarning`` subclasses).
    """
    import warnings as _warnings

    result = _core_predict(lower, upper, **options)
    for w in result.warnings:
        category = WARNING_CATEGORIES.get(w.code, FrictalWarning)
        _warnings.warn(f"[{w.code}] {w.message}", category, stacklevel=2)
    return result


from ._core import predict as _core_predict  # noqa: E402

__all__ = [name for name in dir() if not name.startswith("_")]
