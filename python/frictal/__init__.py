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

from ._core import read_tilt_frames, tilt, tilt_settings  # noqa: F401  spheropolygon tilting-block test (dem_bindings.cpp)
from ._core import areal_tilt, areal_tilt_hold, areal_tilt_settings  # noqa: F401  3D tilt test (dem_bindings.cpp)
from ._core import __version__, build_info  # noqa: F401  version defined once, in CMakeLists.txt

from ._core import (  # noqa: F401  studies: run a study file, read its store (study_bindings.cpp)
    study_export,
    study_findings,
    study_kinds,
    study_report,
    study_rows,
    study_run,
    study_run_many,
    study_status,
)

from ._core import Prediction, prediction_columns, warning_codes  # noqa: F401  the prediction (predict_bindings.cpp)
from ._core import conditioning_settings, predict_settings  # noqa: F401  their keywords' tables (predict_bindings.cpp)
from ._core import signature_settings  # noqa: F401  signature()'s keywords' table (module.cpp)
from ._core import anisotropy_settings, areal_signature_settings  # noqa: F401  their keywords' tables (io_bindings.cpp)


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
    2-D: a map with rows along y) with ``spacing=`` in metres. Options (SI: radians, metres): the
    fields of ``predict_settings()`` and ``conditioning_settings()`` (name, unit, default, valid
    range and meaning of each; ``frictal settings`` lists the same tables): ``direction`` (profiles:
    0 or pi), ``atomic_friction``; the stated test: ``runaway_distance`` d (m; None: 12.5 slope
    correlation lengths of the lower scan, periodic profiles one period) and, for profiles,
    ``block_length`` L_b (m; the middle piece of the upper surface that slides, dropped wherever it
    lies wholly on the lower one; None: 20 d; ``"whole"``: the whole upper profile over the first
    half of the lower one); where the scans cannot hold the test, a defaulted length gives way
    (warning ``scan-too-short``) and stated lengths that do not fit raise ValueError; ``period``;
    for maps ``drops`` (N x N), ``locked`` (the locked diagnostic), ``in_place`` (the upper map in
    place, not turned over), ``sphere_radius``, ``map_work_limit``; the conditioning ``detrend``
    ("none", "mean", "line", "plane", "poly:N"; default line for profiles, plane for maps),
    ``crop`` ("x0,x1[,y0,y1]" with units, or (x0, x1) / (x0, x1, y0, y1) in m: keep that window of
    each surface first), ``remove_spikes`` (replace, for maps mask, the points more than
    ``spike_threshold`` rms heights from the median of their neighbours, after the crop and before
    the form; default 10). Besides the tables:
    ``start_offset`` (x, or (x, y) for maps: one drop), ``drops`` (maps: N x N), ``locked``
    (maps: the locked diagnostic), ``format``, ``unit`` (the files' lengths, x and z: "m", "mm",
    "um", "nm", overriding the units a file names), ``x_unit`` / ``z_unit`` (the lateral lengths or
    the heights alone), ``threads``. Friction under load (profiles and maps; docs/load.md): ``load``
    (the upper block's weight W in N, or a list: the first the headline, the friction-against-load
    curve over all; one load: over W x 10^(-2..1) for profiles, W x 10^(-1..1) for maps), ``modulus`` (Young's modulus E, Pa) and ``poisson``
    (nu) of the lower block, and of the upper one unless ``upper_modulus`` (Pa, or ``"rigid"``) /
    ``upper_poisson``; the result then also has ``load``, ``load_curve``, ``load_curve_median``,
    ``load_curve_q05``, ``load_curve_q95`` and ``rigid_friction_angle``.

    Returns a ``Prediction``: SI attributes (``friction_angle`` is the median over drops of the hold
    angle, atomic friction included; ``upper_bound_friction_angle`` is theta_max + theta_a;
    ``runaway_distance``, ``block_length`` and ``test_lengths`` state the test; ``d_sweep``,
    ``d_sweep_median``, ``d_sweep_q05``, ``d_sweep_q95`` the answer at d/4 .. 4d) and
    ``to_dict()`` with the keys and units of ``frictal predict --json``. Each of its warnings is also
    issued through ``warnings.warn`` with the category of its code (``FrictalWarning`` subclasses).
    ``trust`` is "ok", or "doubtful" where a warning says the input was probably read wrong or the
    load model does not hold for it (``trust_codes``); ``trust_fix`` then names the keywords (and
    CLI options) that fix it, e.g. ``z_unit='um'``.
    """
    import warnings as _warnings

    result = _core_predict(lower, upper, **options)
    for w in result.warnings:
        category = WARNING_CATEGORIES.get(w.code, FrictalWarning)
        _warnings.warn(f"[{w.code}] {w.message}", category, stacklevel=2)
    return result


from ._core import predict as _core_predict  # noqa: E402


def contact(lower, upper=None, **options):
    """Elastic normal contact of rough surfaces: the same solution as ``frictal contact``.

    ``lower`` alone is an elastic body (``modulus`` E in Pa, ``poisson`` nu) pressed against a
    rigid flat; with ``upper`` the two bodies' composite topography is (``upper_modulus``/``upper_poisson``,
    default the same material; ``upper_modulus=float("inf")``: a rigid upper). Surfaces as for
    :func:`predict`. ``load`` (the force: N for maps, N/m per unit depth for profiles) or
    ``pressure`` (nominal, Pa): a number, or a list for a load curve (each load starts from the
    previous solution). ``hardness`` (Pa) caps the pressure (perfect plasticity); ``periodic``
    takes the surface as repeating (else it is padded); ``fields=True`` adds the ``pressure`` and
    ``gap`` arrays. Returns a dict (a list of dicts for a list of loads) with the keys of
    ``frictal contact --json`` without their unit suffix, in SI (m, Pa, N): ``contact_area``,
    ``contact_area_fraction``, ``max_pressure``, ``mean_separation``, ``contact_stiffness``, ... Warnings
    (``small-slope``, ``contact-full``, ...) are in ``warnings`` and issued through
    ``warnings.warn``.
    """
    result = _core_contact(lower, upper, **options)
    seen = set()
    for d in result if isinstance(result, list) else [result]:
        for w in d["warnings"]:
            if (w["code"], w["message"]) not in seen:
                seen.add((w["code"], w["message"]))
                _warn_all([w])
    return result


from ._core import contact as _core_contact  # noqa: E402
from ._core import check_dimension_fit, check_friction_bound, check_map, check_profile  # noqa: E402,F401


def _warn_all(items, stacklevel=3):
    """Issues each warning (a Warning, or a dict with code and message) with its code's category."""
    import warnings as _warnings

    for w in items:
        code, message = (w["code"], w["message"]) if isinstance(w, dict) else (w.code, w.message)
        _warnings.warn(f"[{code}] {message}", WARNING_CATEGORIES.get(code, FrictalWarning), stacklevel=stacklevel)


def _as_dicts(items):
    return [{"code": w.code, "message": w.message} for w in items]


def _wrap(core, checks, doc_note):
    """A function of the core module whose dict result gains ``warnings`` ([{code, message}]): those
    the core put there and those of ``checks(args, kwargs, result)``, each also issued through
    ``warnings.warn`` with its code's category (frictal.FrictalWarning subclasses)."""
    import functools

    @functools.wraps(core)
    def wrapper(*args, **kwargs):
        result = core(*args, **kwargs)
        if not isinstance(result, dict):
            return result
        found = list(result.get("warnings", []) or [])
        for w in _as_dicts(checks(args, kwargs, result)):
            if w not in found:
                found.append(w)
        result["warnings"] = found
        _warn_all(found)
        return result

    wrapper.__doc__ = (core.__doc__ or "") + "\n\n" + doc_note
    return wrapper


def _arg(args, kwargs, index, name, default=None):
    return args[index] if len(args) > index else kwargs.get(name, default)


def _profile_checks(args, kwargs, result):
    out = []
    lower = _arg(args, kwargs, 0, "lower", _arg(args, kwargs, 0, "profile"))
    upper = _arg(args, kwargs, 1, "upper")
    if isinstance(lower, Profile):
        out += check_profile(lower, "lower" if upper is not None else "profile")
    if isinstance(upper, Profile):
        out += check_profile(upper, "upper")
    return out


def _map_checks(args, kwargs, result):
    import numpy as _np

    out = []
    heights = _arg(args, kwargs, 0, "heights", _arg(args, kwargs, 0, "lower"))
    dx, dy = kwargs.get("dx"), kwargs.get("dy")
    if heights is not None and dx is not None and dy is not None:
        out += check_map(_np.asarray(heights, dtype=float), dx=dx, dy=dy, name="lower")
        upper = kwargs.get("upper")
        if upper is not None:
            out += check_map(_np.asarray(upper, dtype=float), dx=dx, dy=dy, name="upper")
    return out


def _fit_checks(method):
    return lambda args, kwargs, r: check_dimension_fit(r["dimension"], r["r_squared"], method)


def _no_checks(args, kwargs, result):
    return []


signature = _wrap(signature, _no_checks,
                  "Warnings: ``warnings`` in the result holds the readers' notes, the plausibility codes of the "
                  "conditioned profiles and the bounds' codes (bound-negative, eq18-low-clamped, "
                  "friction-angle-at-90) ([{code, message}]), as `frictal signature` gives them, each also issued "
                  "with warnings.warn.")
profile_stats = _wrap(profile_stats, _profile_checks, "Warnings: ``warnings`` holds the profile's plausibility codes.")
hold_angle = _wrap(hold_angle, _no_checks, "Warnings: ``warnings`` holds the readers' notes and the conditioned "
                   "profiles' plausibility codes.")
areal_signature = _wrap(areal_signature, _map_checks, "Warnings: ``warnings`` holds the maps' plausibility codes and "
                        "the bound's (eq18-low-clamped, bound-negative), as `frictal areal` gives them.")
areal_hold = _wrap(areal_hold, _no_checks, "Warnings: ``warnings`` holds the prediction's codes (the maps' plausibility "
                   "codes among them).")
map_stats = _wrap(map_stats, _map_checks, "Warnings: ``warnings`` holds the map's plausibility codes.")
anisotropy = _wrap(anisotropy, _map_checks, "Warnings: ``warnings`` holds the map's plausibility codes and each "
                   "direction's bound codes, as `frictal anisotropy` gives them.")
divider_dimension = _wrap(divider_dimension, _fit_checks("divider"), "Warnings: dimension-out-of-range, poor-fit.")
box_dimension = _wrap(box_dimension, _fit_checks("box"), "Warnings: dimension-out-of-range, poor-fit.")
psd_dimension = _wrap(psd_dimension, _fit_checks("psd"), "Warnings: dimension-out-of-range, poor-fit.")
read_surface = _wrap(read_surface, _no_checks, "Warnings: the reader's ([{code, message}], code reader), also issued.")
tilt = _wrap(tilt, _no_checks, "Warnings: the run's codes (e.g. rotation) are also issued with warnings.warn.")
areal_tilt = _wrap(areal_tilt, _no_checks, "Warnings: the run's codes are also issued with warnings.warn.")

predict_friction = _wrap(predict_friction, _no_checks,
                         "Warnings: eq18-low-clamped when the low end of Eq. 18 was clamped at 0, bound-negative "
                         "when the rigid bound is below 0.")

__all__ = [name for name in dir() if not name.startswith("_")]
