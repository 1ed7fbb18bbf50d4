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

__all__ = [name for name in dir() if not name.startswith("_")]
