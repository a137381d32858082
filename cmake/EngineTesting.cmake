# What every test folder uses (included before the engine, its plugins and the sample game add theirs):
# GoogleTest with gtest_discover_tests, and WINDOW_TEST_ENVIRONMENT for the window tests'
# ENVIRONMENT_MODIFICATION.
#
# Sanitizer builds (preset `sanitize`): the window tests run with tests/sanitize/keep_modules_loaded.c
# preloaded, so that libraries unloaded at exit do not turn their caches into unnamed "leaks".
find_package(GTest REQUIRED)
include(GoogleTest)

set(WINDOW_TEST_ENVIRONMENT "")
if(CMAKE_CXX_FLAGS MATCHES "-fsanitize=[a-z,]*address")
  add_library(keep_modules_loaded SHARED ${CMAKE_SOURCE_DIR}/tests/sanitize/keep_modules_loaded.c)
  target_compile_options(keep_modules_loaded PRIVATE -fno-sanitize=all)
  target_link_options(keep_modules_loaded PRIVATE -fno-sanitize=all)
  # libasan must come first among the loaded libraries unless told otherwise.
  set(WINDOW_TEST_ENVIRONMENT
    "LD_PRELOAD=path_list_prepend:$<TARGET_FILE:keep_modules_loaded>"
    "ASAN_OPTIONS=string_append::verify_asan_link_order=0")
endif()
