# Libraries the readers and writers need: libzip (X3P archives), pugixml (X3P main.xml),
# OpenSSL (MD5 checksums through EVP) and zlib (gzip-compressed text, .txt.gz/.csv.gz). Linked privately: they do not appear in public headers.
find_package(PkgConfig REQUIRED)
pkg_check_modules(LIBZIP REQUIRED IMPORTED_TARGET libzip)
find_package(pugixml REQUIRED)
find_package(OpenSSL REQUIRED)
find_package(ZLIB REQUIRED)
target_link_libraries(frictal PRIVATE PkgConfig::LIBZIP pugixml::pugixml OpenSSL::Crypto ZLIB::ZLIB)
# Their headers, for the modules that include them (the objects are linked into frictal above).
target_link_libraries(frictal_io PRIVATE PkgConfig::LIBZIP pugixml::pugixml OpenSSL::Crypto ZLIB::ZLIB)
target_link_libraries(frictal_report PRIVATE ZLIB::ZLIB)

# Gwyddion backend (src/io/gwyddion.cpp): Gwyddion's libraries are loaded at run time with
# dlopen(), so no Gwyddion or GLib header is needed to build and frictal runs without them.
# FRICTAL_GWYDDION: AUTO (compile the backend; report whether the libraries and file modules are
# present now), ON (the same, but fail when libgwyapp2 is not found), OFF (no backend).
set(FRICTAL_GWYDDION AUTO CACHE STRING "Gwyddion reader backend: AUTO, ON or OFF")
set_property(CACHE FRICTAL_GWYDDION PROPERTY STRINGS AUTO ON OFF)
if(NOT FRICTAL_GWYDDION STREQUAL "OFF")
  find_library(FRICTAL_GWYAPP_LIBRARY NAMES libgwyapp2.so.0 gwyapp2)
  # The file-module directory: pkg-config's gwymoduledir when the development files are
  # complete, else Debian's multiarch path.
  set(_gwy_moddir "/usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}/gwyddion/modules")
  pkg_check_modules(GWYDDION QUIET gwyddion)
  if(GWYDDION_FOUND)
    pkg_get_variable(_gwy_pc_moddir gwyddion gwymoduledir)
    if(_gwy_pc_moddir)
      set(_gwy_moddir "${_gwy_pc_moddir}")
    endif()
  endif()
  set(FRICTAL_GWYDDION_MODULE_DIR "${_gwy_moddir}" CACHE PATH "Directory of Gwyddion's modules (holds file/)")
  if(FRICTAL_GWYDDION STREQUAL "ON" AND NOT FRICTAL_GWYAPP_LIBRARY)
    message(FATAL_ERROR "FRICTAL_GWYDDION=ON but libgwyapp2 was not found (install libgwyddion2-0 and gwyddion)")
  endif()
  target_compile_definitions(frictal_io PRIVATE FRICTAL_GWYDDION_ENABLED=1
    FRICTAL_GWYDDION_MODULE_DIR="${FRICTAL_GWYDDION_MODULE_DIR}")
  target_link_libraries(frictal PRIVATE ${CMAKE_DL_LIBS})
  if(NOT FRICTAL_GWYAPP_LIBRARY)
    message(STATUS "frictal: Gwyddion backend compiled, but libgwyapp2 is not installed: Gwyddion formats will report the packages to install")
  elseif(NOT EXISTS "${FRICTAL_GWYDDION_MODULE_DIR}/file")
    message(STATUS "frictal: Gwyddion libraries found, but no file modules in ${FRICTAL_GWYDDION_MODULE_DIR}/file (Debian package gwyddion)")
  else()
    message(STATUS "frictal: Gwyddion backend with the file modules in ${FRICTAL_GWYDDION_MODULE_DIR}/file")
  endif()
endif()
