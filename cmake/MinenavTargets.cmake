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
function(minenav_algorithm_library name)
  add_library(${name} STATIC ${ARGN})
  target_include_directories(${name} BEFORE PRIVATE ${MINENAV_NO_LCM_DIRS})
  target_include_directories(${name} PUBLIC "${CMAKE_SOURCE_DIR}")
  minenav_warnings(${name})
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

# minenav_test(NAME name SOURCES ... LIBS ... [LABELS ...] [NO_LCM])
# A GoogleTest binary registered with CTest, one CTest test per TEST().
function(minenav_test)
  cmake_parse_arguments(ARG "NO_LCM" "NAME;TIMEOUT" "SOURCES;LIBS;LABELS" ${ARGN})
  add_executable(${ARG_NAME} ${ARG_SOURCES})
  target_include_directories(${ARG_NAME} PRIVATE "${CMAKE_SOURCE_DIR}")
  if(ARG_NO_LCM)
    target_include_directories(${ARG_NAME} BEFORE PRIVATE ${MINENAV_NO_LCM_DIRS})
  endif()
  target_link_libraries(${ARG_NAME} PRIVATE ${ARG_LIBS} GTest::gtest_main GTest::gmock)
  minenav_warnings(${ARG_NAME})
  set_target_properties(${ARG_NAME} PROPERTIES RUNTIME_OUTPUT_DIRECTORY "${CMAKE_BINARY_DIR}/tests")
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 300)
  endif()
  gtest_discover_tests(${ARG_NAME}
    WORKING_DIRECTORY "${CMAKE_BINARY_DIR}"
    PROPERTIES TIMEOUT ${ARG_TIMEOUT} LABELS "${ARG_LABELS}"
    DISCOVERY_TIMEOUT 60)
endfunction()
