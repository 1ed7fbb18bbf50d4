# FFTW (Debian libfftw3-dev) for the contact module's convolutions (src/contact/kernel.cpp): the
# real-to-complex transforms of the elastic half-space's Green's function. Linked privately (no
# public header includes it); the static library carries it into a consumer's link
# (frictal-find-fftw3.cmake, included by frictalConfig.cmake). fftw3_threads, when present,
# spreads one transform over the solver's threads.
include(${CMAKE_CURRENT_LIST_DIR}/frictal-find-fftw3.cmake)
target_link_libraries(frictal PRIVATE PkgConfig::FFTW3)
target_link_libraries(frictal_contact PRIVATE PkgConfig::FFTW3)
if(TARGET FFTW3::threads)
  target_link_libraries(frictal PRIVATE FFTW3::threads)
  target_compile_definitions(frictal_contact PRIVATE FRICTAL_FFTW_THREADS=1)
endif()
