# Sanitizer builds (scripts/sanitize.sh, README "Sanitizers").
#
# BINPICK_SANITIZE=address,undefined   AddressSanitizer (with LeakSanitizer) and UndefinedBehaviorSanitizer;
#                                      any UB report aborts (-fno-sanitize-recover=all)
# BINPICK_SANITIZE=thread              ThreadSanitizer, with OpenMP off (below)
#
# Every target is compiled with -fsanitize=... -fno-omit-frame-pointer -g -O1 (the -O1 comes after the
# build type's -O, so it wins) and linked with the same -fsanitize. Included after find_package(OpenMP).
set(BINPICK_SANITIZE "" CACHE STRING
    "Build with sanitizers: address,undefined or thread (empty: none; scripts/sanitize.sh)")

if(BINPICK_SANITIZE)
  string(REPLACE "," ";" binpick_sanitizers "${BINPICK_SANITIZE}")
  foreach(sanitizer IN LISTS binpick_sanitizers)
    if(NOT sanitizer MATCHES "^(address|undefined|thread)$")
      message(FATAL_ERROR "BINPICK_SANITIZE: unknown sanitizer '${sanitizer}' (address, undefined, thread)")
    endif()
  endforeach()
  if("thread" IN_LIST binpick_sanitizers AND "address" IN_LIST binpick_sanitizers)
    message(FATAL_ERROR "BINPICK_SANITIZE: thread and address cannot be combined; build them separately")
  endif()

  set(binpick_sanitize_flag "-fsanitize=${BINPICK_SANITIZE}")
  add_compile_options(${binpick_sanitize_flag} -fno-omit-frame-pointer -g -O1)
  add_link_options(${binpick_sanitize_flag})
  # GCC warns of "maybe uninitialized" values it cannot follow through the sanitizers' checks
  # (in libstdc++'s <regex> here): noise, with no bearing on the code the sanitizers check.
  add_compile_options(-Wno-maybe-uninitialized)
  if("undefined" IN_LIST binpick_sanitizers)
    # A UB report stops the process (exit code and report), so that no test passes over one.
    add_compile_options(-fno-sanitize-recover=all)
  endif()

  if("thread" IN_LIST binpick_sanitizers)
    # No OpenMP under ThreadSanitizer: libgomp is not built with TSan, so the barriers and the
    # thread pool it reuses between parallel regions are invisible to it, and every `omp parallel`
    # loop over shared arrays is reported as a race in our own code (a false positive that could
    # only be suppressed by suppressing our own functions). OMP_NUM_THREADS does not help: the
    # loops ask for their thread count with num_threads(). So the pragmas are ignored and the loops
    # run serially; TSan checks the project's own threads (robot server, web server, cell service,
    # binpickd). The OpenMP loops are checked by the AddressSanitizer build, which keeps OpenMP.
    set_property(TARGET OpenMP::OpenMP_CXX PROPERTY INTERFACE_COMPILE_OPTIONS -Wno-unknown-pragmas)
    set_property(TARGET OpenMP::OpenMP_CXX PROPERTY INTERFACE_LINK_LIBRARIES "")
  endif()
  # A test runs 5 to 20 times slower under the sanitizers (the daemon's soak, 30 s in a release
  # build, takes over 300 s under TSan), so ctest's hang guard for the GoogleTest suites
  # (cmake/BinpickTargets.cmake, included before this file) waits four times as long. What the
  # tests check is unchanged.
  set(BINPICK_TEST_TIMEOUT 1200)
  message(STATUS "binpick: sanitizers ${BINPICK_SANITIZE}")
endif()

# binpick_add_suite_target(NAME DIRECTORIES dir... [TARGETS target...] [MATCHING regex])
#   A target that builds every executable defined in the DIRECTORIES (relative to the source
#   tree, with their subdirectories), the TARGETS, and every executable of the project whose name
#   matches MATCHING: what those suites need to run, and no more (scripts/sanitize.sh builds
#   `sanitize_suites`).
function(binpick_add_suite_target name)
  cmake_parse_arguments(ARG "" "MATCHING" "DIRECTORIES;TARGETS" ${ARGN})
  set(executables ${ARG_TARGETS})
  set(pending ${PROJECT_SOURCE_DIR})
  while(pending)
    list(POP_FRONT pending directory)
    set(whole FALSE)
    foreach(chosen IN LISTS ARG_DIRECTORIES)
      string(FIND "${directory}/" "${PROJECT_SOURCE_DIR}/${chosen}/" at)
      if(at EQUAL 0)
        set(whole TRUE)
      endif()
    endforeach()
    get_property(targets DIRECTORY ${directory} PROPERTY BUILDSYSTEM_TARGETS)
    foreach(target IN LISTS targets)
      get_target_property(type ${target} TYPE)
      if(type STREQUAL "EXECUTABLE" AND (whole OR (ARG_MATCHING AND target MATCHES "${ARG_MATCHING}")))
        list(APPEND executables ${target})
      endif()
    endforeach()
    get_property(subdirectories DIRECTORY ${directory} PROPERTY SUBDIRECTORIES)
    list(APPEND pending ${subdirectories})
  endwhile()
  add_custom_target(${name})
  add_dependencies(${name} ${executables})
endfunction()
