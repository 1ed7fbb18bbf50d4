# frictal's modules (included by the top-level CMakeLists.txt after add_library(frictal)).
#
# src/tiers.txt lists the modules in tier order: "module : uses | public headers | shared headers".
# Each module is an OBJECT library frictal_<module> whose sources src/<module>/CMakeLists.txt lists
# (target_sources), linked to the modules it uses (their usage requirements; nothing links
# upward). Its private include path is a folder of the build tree, tiers/<module>/, that holds
# links to src/<module>/ and src/util/ and to the shared headers of the modules below it, so
# that "other/private.hpp" of any other module is not found. The public headers are one folder
# (include/frictal/): scripts/check-tiers.py, run before any module compiles, fails the build
# with the file, line and rule of an include that goes to a public header of a module not below.

set(FRICTAL_MODULES)
file(STRINGS ${CMAKE_CURRENT_SOURCE_DIR}/src/tiers.txt _frictal_tier_lines)
foreach(_line IN LISTS _frictal_tier_lines)
  string(REGEX REPLACE "#.*" "" _line "${_line}")
  if(NOT _line MATCHES "^([a-z_]+) *:([^|]*)\\|([^|]*)\\|(.*)$")
    continue()
  endif()
  set(_module ${CMAKE_MATCH_1})
  separate_arguments(_uses UNIX_COMMAND "${CMAKE_MATCH_2}")
  separate_arguments(_shared UNIX_COMMAND "${CMAKE_MATCH_4}")
  if(_module STREQUAL "base")
    continue()
  endif()
  list(APPEND FRICTAL_MODULES ${_module})
  set(FRICTAL_MODULE_USES_${_module} ${_uses})
  set(FRICTAL_MODULE_SHARED_${_module} ${_shared})
endforeach()

# The check of the includes against the tiers; every module (hence frictal) depends on it.
find_program(FRICTAL_PYTHON NAMES python3 python)
if(FRICTAL_PYTHON)
  file(GLOB_RECURSE _frictal_tier_inputs CONFIGURE_DEPENDS
       ${CMAKE_CURRENT_SOURCE_DIR}/src/*.cpp ${CMAKE_CURRENT_SOURCE_DIR}/src/*.hpp
       ${CMAKE_CURRENT_SOURCE_DIR}/include/frictal/*.hpp)
  add_custom_command(OUTPUT ${CMAKE_CURRENT_BINARY_DIR}/tiers/check.stamp
    COMMAND ${FRICTAL_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check-tiers.py ${CMAKE_CURRENT_SOURCE_DIR}
            --stamp ${CMAKE_CURRENT_BINARY_DIR}/tiers/check.stamp
    DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check-tiers.py ${CMAKE_CURRENT_SOURCE_DIR}/src/tiers.txt
            ${_frictal_tier_inputs}
    COMMENT "frictal: includes against the module tiers (src/tiers.txt)" VERBATIM)
  add_custom_target(frictal_tiers DEPENDS ${CMAKE_CURRENT_BINARY_DIR}/tiers/check.stamp)
else()
  message(STATUS "frictal: no Python interpreter: the includes are not checked against src/tiers.txt")
endif()

foreach(_module IN LISTS FRICTAL_MODULES)
  add_library(frictal_${_module} OBJECT)
  # The private include path: tiers/<module>/ with <module> and util linked whole and the shared
  # headers of the modules below, one link each.
  set(_dir ${CMAKE_CURRENT_BINARY_DIR}/tiers/${_module})
  file(REMOVE_RECURSE ${_dir})
  file(MAKE_DIRECTORY ${_dir})
  file(CREATE_LINK ${CMAKE_CURRENT_SOURCE_DIR}/src/${_module} ${_dir}/${_module} SYMBOLIC)
  if(NOT _module STREQUAL "util")
    file(CREATE_LINK ${CMAKE_CURRENT_SOURCE_DIR}/src/util ${_dir}/util SYMBOLIC)
  endif()
  set(_below ${FRICTAL_MODULE_USES_${_module}})
  set(_seen)
  while(_below)
    list(POP_FRONT _below _m)
    if(_m IN_LIST _seen OR _m STREQUAL "util")
      continue()
    endif()
    list(APPEND _seen ${_m})
    list(APPEND _below ${FRICTAL_MODULE_USES_${_m}})
    foreach(_h IN LISTS FRICTAL_MODULE_SHARED_${_m})
      file(MAKE_DIRECTORY ${_dir}/${_m})
      file(CREATE_LINK ${CMAKE_CURRENT_SOURCE_DIR}/src/${_m}/${_h} ${_dir}/${_m}/${_h} SYMBOLIC)
    endforeach()
  endwhile()
  target_include_directories(frictal_${_module}
    PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include> PRIVATE ${_dir})
  target_link_libraries(frictal_${_module} PRIVATE fmt::fmt Threads::Threads)
  foreach(_m IN LISTS FRICTAL_MODULE_USES_${_module})
    target_link_libraries(frictal_${_module} PUBLIC frictal_${_m})
  endforeach()
  if(TARGET frictal_tiers)
    add_dependencies(frictal_${_module} frictal_tiers)
  endif()
  add_subdirectory(src/${_module})
  target_sources(frictal PRIVATE $<TARGET_OBJECTS:frictal_${_module}>)
endforeach()
