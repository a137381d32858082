# Fuzz harnesses of the engine and its plugins (tests/fuzz/README.md). Each <name>_fuzz.cpp defines
# LLVMFuzzerTestOneInput. With ENGINE_FUZZERS (the `fuzz` preset, clang) each becomes a libFuzzer
# executable fuzz_<name>, all built by the target `fuzzers`; in every other build each is linked
# with tests/fuzz/replay_main.cpp as fuzz_replay_<name>, and ctest replays the committed regression
# inputs and seeds (test fuzz.<name>, label unit), so every crash once found stays a test.
option(ENGINE_FUZZERS "Build the libFuzzer harnesses (clang with -fsanitize=fuzzer-no-link; preset fuzz)" OFF)
if(ENGINE_FUZZERS)
  add_custom_target(fuzzers)
endif()

# engine_fuzz_harness(<name> MAX_LEN <bytes> LIBS <libraries>): the harness <name>_fuzz.cpp of the
# calling folder, whose seeds/<name>/, regressions/<name>/ and dicts/<name>.dict sit beside it.
# MAX_LEN is the largest input libFuzzer makes (scripts/fuzz passes it as -max_len). The harness is
# listed, with its folder, in <build>/fuzz_harnesses.txt for scripts/fuzz.
function(engine_fuzz_harness name)
  cmake_parse_arguments(H "" "MAX_LEN" "LIBS" ${ARGN})
  set(dir ${CMAKE_CURRENT_SOURCE_DIR})
  if(ENGINE_FUZZERS)
    set(target fuzz_${name})
    add_executable(${target} ${dir}/${name}_fuzz.cpp)
    target_link_options(${target} PRIVATE -fsanitize=fuzzer)
    add_dependencies(fuzzers ${target})
    # libFuzzer replays files and folders itself; -runs=0 runs the corpus once without fuzzing.
    set(command $<TARGET_FILE:${target}> -runs=0)
  else()
    set(target fuzz_replay_${name})
    add_executable(${target} ${dir}/${name}_fuzz.cpp ${PROJECT_SOURCE_DIR}/tests/fuzz/replay_main.cpp)
    set(command $<TARGET_FILE:${target}>)
  endif()
  target_link_libraries(${target} PRIVATE ${H_LIBS})
  engine_set_warnings(${target})
  add_test(NAME fuzz.${name} COMMAND ${command} ${dir}/regressions/${name} ${dir}/seeds/${name})
  set_tests_properties(fuzz.${name} PROPERTIES LABELS unit TIMEOUT 120)
  file(RELATIVE_PATH rel_dir ${PROJECT_SOURCE_DIR} ${dir})
  file(RELATIVE_PATH rel_bin ${PROJECT_BINARY_DIR} ${CMAKE_CURRENT_BINARY_DIR})
  set_property(GLOBAL APPEND PROPERTY ENGINE_FUZZ_LIST "${name} ${H_MAX_LEN} ${rel_dir} ${rel_bin}")
endfunction()

# For scripts/fuzz: one "name max_len source_folder build_folder" line per harness.
function(engine_write_fuzz_list)
  get_property(entries GLOBAL PROPERTY ENGINE_FUZZ_LIST)
  list(JOIN entries "\n" text)
  file(WRITE ${PROJECT_BINARY_DIR}/fuzz_harnesses.txt "${text}\n")
endfunction()
