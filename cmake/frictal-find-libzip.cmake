# libzip as frictal found it at build time (pkg-config), for consumers of the installed package.
if(NOT TARGET PkgConfig::LIBZIP)
  find_package(PkgConfig REQUIRED)
  pkg_check_modules(LIBZIP REQUIRED IMPORTED_TARGET libzip)
endif()
