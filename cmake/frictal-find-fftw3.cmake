# FFTW (double precision) as frictal finds it (pkg-config fftw3), at build time and for consumers
# of the installed package: PkgConfig::FFTW3, and FFTW3::threads when libfftw3_threads is there.
if(NOT TARGET PkgConfig::FFTW3)
  find_package(PkgConfig REQUIRED)
  pkg_check_modules(FFTW3 REQUIRED IMPORTED_TARGET fftw3)
endif()
if(NOT TARGET FFTW3::threads)
  find_library(FRICTAL_FFTW3_THREADS_LIBRARY NAMES fftw3_threads HINTS ${FFTW3_LIBRARY_DIRS})
  if(FRICTAL_FFTW3_THREADS_LIBRARY)
    add_library(FFTW3::threads UNKNOWN IMPORTED)
    set_target_properties(FFTW3::threads PROPERTIES IMPORTED_LOCATION ${FRICTAL_FFTW3_THREADS_LIBRARY}
                                                    INTERFACE_LINK_LIBRARIES PkgConfig::FFTW3)
  endif()
endif()
