# Helpers that give every target the same warnings and keep LCM out of algorithm code.

# cmake/no_lcm/lcm/ holds headers named like LCM's that #error; the generated
# no_lcm/minenav/ does the same for every message type (see minenav_lcm_types).
set(MINENAV_NO_LCM_DIRS "${CMAKE_SOURCE_DIR}/cmake/no_lcm" "${CMAKE_BINARY_DIR}/no_lcm")

function(minenav_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow
    -Wnon-virtual-dtor -Wold-style-cast -Wcast-align -Woverloaded-virtual
    -Wconversion -Wno-sign-conversion -Wimplicit-fallthrough)
  if(MINENAV_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# An algorithm library: plain C++, no LCM. The no_lcm directories come first on its
# include path and hold headers named like LCM's and like our message types that
# #error, so `#include <lcm/lcm-cpp.hpp>` in algorithm code fails to compile.
# Under the sanitizers an algorithm library keeps -O2 (the rest of that build is -O1 and the
# test files -O0, CMakeLists.txt): the arithmetic is here, the timing bounds of the tests were
# set against it, and at -O1 the contour fit under ASan took 6.3 s a scan (a stop request and
# a 3000-scan backlog then missed their bounds).
function(minenav_algorithm_library name)
  add_library(${name} STATIC ${ARGN})
  target_include_directories(${name} BEFORE PRIVATE ${MINENAV_NO_LCM_DIRS})
  target_include_directories(${name} PUBLIC "${CMAKE_SOURCE_DIR}")
  minenav_warnings(${name})
  if(MINENAV_SANITIZE)
    target_compile_options(${name} PRIVATE -O2)
  endif()
endfunction()

# A library or executable that may talk LCM (nodes, tools).
function(minenav_node_library name)
  add_library(${name} STATIC ${ARGN})
  target_include_directories(${name} PUBLIC "${CMAKE_SOURCE_DIR}")
  minenav_warnings(${name})
endfunction()

function(minenav_executable name)
  add_executable(${name} ${ARGN})
  target_include_directories(${name} PRIVATE "${CMAKE_SOURCE_DIR}")
  minenav_warnings(${name})
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY "${CMAKE_BINARY_DIR}/bin")
endfunction()

# Under the sanitizers the test files themselves (*_test.cc: GoogleTest's macros, set-up and
# checks) compile at -O0, the code they test at -O1 or -O2 (above): ASan+UBSan at -O1 cost a
# test file 3.2x its -O0 compile (planner/se2_planner_test.cc: 31.7 s against 9.9 s), and the
# time a test runs is spent in the libraries, not in its assertions (a timing bound on a
# header template the test instantiates is scaled by tests/sanitizer.h's kSlowdown). Helpers
# of the tests (testing/*.cc: the closed-loop simulations) keep -O1.
function(minenav_sanitized_test_at_o0 target)
  if(NOT MINENAV_SANITIZE)
    return()
  endif()
  get_target_property(sources ${target} SOURCES)
  foreach(source IN LISTS sources)
    if(source MATCHES "_test\\.cc$")
      set_property(SOURCE "${source}" APPEND PROPERTY COMPILE_OPTIONS -O0)
    endif()
  endforeach()
endfunction()

# minenav_test_program(name source...): a test program that CMake files register with their own
# add_test (bus and process tests: a private network namespace, a port, a filter): tests/ as its
# folder, the warnings, and its *_test.cc at -O0 under the sanitizers, as minenav_test's.
function(minenav_test_program name)
  add_executable(${name} ${ARGN})
  target_include_directories(${name} PRIVATE "${CMAKE_SOURCE_DIR}")
  minenav_warnings(${name})
  minenav_sanitized_test_at_o0(${name})
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY "${CMAKE_BINARY_DIR}/tests")
endfunction()

# minenav_test(NAME name SOURCES ... LIBS ... [LABELS ...] [NO_LCM])
# A GoogleTest binary registered with CTest, one CTest test per TEST().
function(minenav_test)
  cmake_parse_arguments(ARG "NO_LCM" "NAME;TIMEOUT" "SOURCES;LIBS;LABELS" ${ARGN})
  minenav_test_program(${ARG_NAME} ${ARG_SOURCES})
  if(ARG_NO_LCM)
    target_include_directories(${ARG_NAME} BEFORE PRIVATE ${MINENAV_NO_LCM_DIRS})
  endif()
  target_link_libraries(${ARG_NAME} PRIVATE ${ARG_LIBS} GTest::gtest_main GTest::gmock)
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 300)
  endif()
  gtest_discover_tests(${ARG_NAME}
    WORKING_DIRECTORY "${CMAKE_BINARY_DIR}"
    PROPERTIES TIMEOUT ${ARG_TIMEOUT} LABELS "${ARG_LABELS}"
    DISCOVERY_TIMEOUT 60)
endfunction()
