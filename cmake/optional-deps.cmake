# Libraries the readers and writers need: libzip (X3P archives), pugixml (X3P main.xml),
# OpenSSL (MD5 checksums through EVP) and zlib (gzip-compressed text, .txt.gz/.csv.gz). Linked privately: they do not appear in public headers.
find_package(PkgConfig REQUIRED)
pkg_check_modules(LIBZIP REQUIRED IMPORTED_TARGET libzip)
find_package(pugixml REQUIRED)
find_package(OpenSSL REQUIRED)
find_package(ZLIB REQUIRED)
target_link_libraries(frictal PRIVATE PkgConfig::LIBZIP pugixml::pugixml OpenSSL::Crypto ZLIB::ZLIB)
