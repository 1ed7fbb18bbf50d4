# Dependencies of the studies module (src/study): SQLite store, TOML study files, MPI runner.
find_package(SQLite3 REQUIRED)
find_package(tomlplusplus REQUIRED)
find_package(nlohmann_json REQUIRED)
target_link_libraries(frictal PRIVATE SQLite::SQLite3 tomlplusplus::tomlplusplus nlohmann_json::nlohmann_json)
target_link_libraries(frictal_study PRIVATE SQLite::SQLite3 tomlplusplus::tomlplusplus nlohmann_json::nlohmann_json)

# MPI: on when an MPI library is found (we call only its C API; see src/study/mpi_runner.cpp).
find_package(MPI QUIET COMPONENTS CXX)
option(FRICTAL_MPI "Distribute study tasks over MPI ranks (frictal study run under mpirun)" ${MPI_CXX_FOUND})
if(FRICTAL_MPI)
  find_package(MPI REQUIRED COMPONENTS CXX)
  target_link_libraries(frictal PRIVATE MPI::MPI_CXX)
  target_link_libraries(frictal_study PRIVATE MPI::MPI_CXX)
  target_compile_definitions(frictal_study PRIVATE FRICTAL_MPI=1)
  message(STATUS "frictal: MPI study runner enabled (${MPIEXEC_EXECUTABLE})")
endif()
