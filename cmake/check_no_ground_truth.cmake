# Run by CTest: compiles a file that includes the simulator with the include path the
# estimators, the mapper and their processes get, and passes only if the compiler refuses
# it with our message (cmake/NoGroundTruth.cmake).
# cmake -DCXX=... -DSOURCE_DIR=... -DBINARY_DIR=... -P check_no_ground_truth.cmake
foreach(header "sim/world.h" "sim/survey.h" "sensor_driver/ladar_simulator.h")
  file(WRITE "${BINARY_DIR}/no_ground_truth_probe.cc" "#include \"${header}\"\nint main() { return 0; }\n")
  execute_process(
    COMMAND "${CXX}" -fsyntax-only -I "${BINARY_DIR}/no_ground_truth" -I "${SOURCE_DIR}"
            "${BINARY_DIR}/no_ground_truth_probe.cc"
    RESULT_VARIABLE result ERROR_VARIABLE err OUTPUT_QUIET)
  if(result EQUAL 0)
    message(FATAL_ERROR "#include \"${header}\" compiled where ground truth is forbidden")
  endif()
  if(NOT err MATCHES "ground truth")
    message(FATAL_ERROR "#include \"${header}\" failed for another reason:\n${err}")
  endif()
endforeach()
message(STATUS "simulator includes are refused in estimators, the mapper and their processes")
