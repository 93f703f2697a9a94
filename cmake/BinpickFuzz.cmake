# binpick_add_fuzz_target: how the fuzz targets of fuzz/ (fuzz/README.md) are built and run in
# ctest. Each runs two ways: PREFIX_fuzz_smoke (any compiler) feeds it seeded mutations of its
# corpus through fuzz/random_input_driver.cpp, and a finding aborts, failing the test;
# PREFIX_libfuzzer (label `fuzz`, when configure found clang++) runs it under libFuzzer with
# AddressSanitizer and UBSan through fuzz/run-libfuzzer.sh, which builds it into a temporary
# directory. `ctest -LE fuzz` leaves those out of a quick run.

set(BINPICK_FUZZ_DIR ${PROJECT_SOURCE_DIR}/fuzz)
find_program(BINPICK_CLANGXX NAMES clang++ clang++-14)
if(BINPICK_CLANGXX)
  get_target_property(BINPICK_EIGEN_INCLUDE Eigen3::Eigen INTERFACE_INCLUDE_DIRECTORIES)
  list(GET BINPICK_EIGEN_INCLUDE 0 BINPICK_EIGEN_INCLUDE)
endif()

# binpick_add_fuzz_target(TARGET TEST PREFIX SMOKE_INPUTS N LIBFUZZER_RUNS N LIBS libs...)
#   fuzz/TARGET_fuzz.cpp with its corpus fuzz/corpus/TARGET, linked with LIBS into
#   TARGET_fuzz_driver; tests PREFIX_fuzz_smoke (N seeded inputs: a few seconds) and
#   PREFIX_libfuzzer (N libFuzzer runs).
function(binpick_add_fuzz_target target)
  cmake_parse_arguments(ARG "" "TEST;SMOKE_INPUTS;LIBFUZZER_RUNS" "LIBS" ${ARGN})
  add_executable(${target}_fuzz_driver ${BINPICK_FUZZ_DIR}/${target}_fuzz.cpp ${BINPICK_FUZZ_DIR}/random_input_driver.cpp)
  target_link_libraries(${target}_fuzz_driver PRIVATE ${ARG_LIBS} binpick_warnings)
  add_test(NAME ${ARG_TEST}_fuzz_smoke
    COMMAND ${target}_fuzz_driver ${BINPICK_FUZZ_DIR}/corpus/${target} ${ARG_SMOKE_INPUTS})
  set_tests_properties(${ARG_TEST}_fuzz_smoke PROPERTIES TIMEOUT 120)
  if(BINPICK_CLANGXX)
    # The file-reader targets link the rest of the project from this build's static libraries.
    add_test(NAME ${ARG_TEST}_libfuzzer
      COMMAND ${CMAKE_COMMAND} -E env CXX=${BINPICK_CLANGXX} EIGEN_INCLUDE_DIR=${BINPICK_EIGEN_INCLUDE}
              BINPICK_BUILD_DIR=${CMAKE_BINARY_DIR} sh ${BINPICK_FUZZ_DIR}/run-libfuzzer.sh ${target} ${ARG_LIBFUZZER_RUNS})
    set_tests_properties(${ARG_TEST}_libfuzzer PROPERTIES TIMEOUT 300 LABELS fuzz)
  endif()
endfunction()
