# Run by CTest: compiles a file that includes LCM with the include path algorithm
# libraries get, and passes only if the compiler refuses it with our message.
# cmake -DCXX=... -DSOURCE_DIR=... -DBINARY_DIR=... -P check_no_lcm.cmake
foreach(header "lcm/lcm-cpp.hpp" "minenav/ladar_scan_t.hpp")
  file(WRITE "${BINARY_DIR}/no_lcm_probe.cc" "#include <${header}>\nint main() { return 0; }\n")
  execute_process(
    COMMAND "${CXX}" -fsyntax-only -I "${SOURCE_DIR}/cmake/no_lcm" -I "${BINARY_DIR}/no_lcm"
            -I "${SOURCE_DIR}" "${BINARY_DIR}/no_lcm_probe.cc"
    RESULT_VARIABLE result ERROR_VARIABLE err OUTPUT_QUIET)
  if(result EQUAL 0)
    message(FATAL_ERROR "#include <${header}> compiled in an algorithm library context")
  endif()
  if(NOT err MATCHES "in an algorithm library")
    message(FATAL_ERROR "#include <${header}> failed for another reason:\n${err}")
  endif()
endforeach()
message(STATUS "LCM includes are refused in algorithm libraries")
