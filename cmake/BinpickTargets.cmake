# The three ways a target is added in this tree.
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

# binpick_add_plugin(NAME LOADED_BY TARGET SOURCES a.cpp ... [INCLUDES dirs...] [LIBS deps...])
#   A plugin of binpick's own (binpick/core/plugin.hpp): the module binpick_NAME, built into the
#   build's plugin directory and installed into lib/binpick, every symbol resolved at link time.
#   TARGET, the library that loads it, is built with it and gets where to look for it as
#   BINPICK_<NAME>_BESIDE_PROGRAM (installed) and BINPICK_<NAME>_IN_BUILD (NAME upper-cased).
function(binpick_add_plugin name)
  cmake_parse_arguments(ARG "" "LOADED_BY" "SOURCES;INCLUDES;LIBS" ${ARGN})
  set(plugin binpick_${name})
  add_library(${plugin} MODULE ${ARG_SOURCES})
  target_include_directories(${plugin} PRIVATE ${ARG_INCLUDES})
  target_link_libraries(${plugin} PRIVATE ${ARG_LIBS} binpick_warnings)
  target_link_options(${plugin} PRIVATE -Wl,--no-undefined)
  set_target_properties(${plugin} PROPERTIES LIBRARY_OUTPUT_DIRECTORY ${BINPICK_PLUGIN_BUILD_DIR})
  string(TOUPPER ${name} macro)
  target_compile_definitions(${ARG_LOADED_BY} PRIVATE
    BINPICK_${macro}_BESIDE_PROGRAM="${BINPICK_PLUGIN_FROM_BINDIR}/$<TARGET_FILE_NAME:${plugin}>"
    BINPICK_${macro}_IN_BUILD="$<TARGET_FILE:${plugin}>")
  add_dependencies(${ARG_LOADED_BY} ${plugin})
  install(TARGETS ${plugin} LIBRARY DESTINATION ${BINPICK_PLUGIN_INSTALL_DIR})
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
