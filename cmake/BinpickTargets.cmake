# The two ways a target is added in this tree.
#
# binpick_add_library(NAME SOURCES a.cpp ... [PUBLIC deps...] [PRIVATE deps...])
#   A module: src/NAME holds include/binpick/NAME/*.hpp (its interface, namespace binpick::NAME)
#   and src/*.cpp with private headers beside them. Defines binpick_NAME and the alias
#   binpick::NAME; warnings are on for the module's own sources only. A header is public only when
#   another module includes it (scripts/check-module-surfaces.py, a ctest). The module's tests and
#   benchmarks reach its private headers through binpick::NAME_internals; no module links that.
function(binpick_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC;PRIVATE" ${ARGN})
  add_library(binpick_${name} ${ARG_SOURCES})
  add_library(binpick::${name} ALIAS binpick_${name})
  target_include_directories(binpick_${name}
    PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/src)
  target_link_libraries(binpick_${name} PUBLIC ${ARG_PUBLIC} PRIVATE ${ARG_PRIVATE} binpick_warnings)
  add_library(binpick_${name}_internals INTERFACE)
  add_library(binpick::${name}_internals ALIAS binpick_${name}_internals)
  target_include_directories(binpick_${name}_internals INTERFACE ${CMAKE_CURRENT_SOURCE_DIR}/src)
  target_link_libraries(binpick_${name}_internals INTERFACE binpick_${name} ${ARG_PRIVATE})
endfunction()

# binpick_add_test(NAME SOURCES a.cpp b.cpp LIBS binpick::io ...)
#   A GoogleTest executable, its tests registered with ctest one by one, each stopped as hung
#   after BINPICK_TEST_TIMEOUT seconds (a sanitizer build raises it: cmake/Sanitize.cmake).
set(BINPICK_TEST_TIMEOUT 300)
function(binpick_add_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_LIBS} GTest::gtest GTest::gtest_main binpick_warnings)
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests/common)
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT ${BINPICK_TEST_TIMEOUT})
endfunction()
