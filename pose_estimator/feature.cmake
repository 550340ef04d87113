# Feature-based pose estimator (thesis chapter 2). Included by pose_estimator/CMakeLists.txt.
minenav_algorithm_library(minenav_feature
  feature_types.cc
  feature_map.cc
  feature_prediction.cc
  incremental_line_fitter.cc
  corner_operator.cc
  feature_extraction.cc
  feature_matching.cc
  feature_minimization.cc
  feature_pose_estimator.cc)
target_link_libraries(minenav_feature PUBLIC minenav_common Eigen3::Eigen)

minenav_test(NAME feature_test NO_LCM
  SOURCES
    feature_prediction_test.cc
    incremental_line_fitter_test.cc
    feature_extraction_test.cc
    feature_matching_test.cc
    feature_minimization_test.cc
    feature_pose_estimator_test.cc
  LIBS minenav_feature)

# The process (thin node over minenav_feature).
if(TARGET minenav_node)
  minenav_executable(feature_pose_estimator feature_pose_estimator_main.cc)
  target_link_libraries(feature_pose_estimator PRIVATE minenav_feature minenav_node)
endif()

# The process in batch (no bus): a log in, poses out, bad input.
if(TARGET feature_pose_estimator AND EXISTS "${CMAKE_SOURCE_DIR}/tests/child_process.cc")
  minenav_test(NAME feature_process_test
    SOURCES feature_pose_estimator_process_test.cc "${CMAKE_SOURCE_DIR}/tests/child_process.cc"
    LIBS minenav_feature minenav_node)
  target_compile_definitions(feature_process_test PRIVATE MINENAV_FPE_BIN="$<TARGET_FILE:feature_pose_estimator>")
  add_dependencies(feature_process_test feature_pose_estimator)
endif()

# Live on the bus with vehicle_sim and ladar_driver, inside a private network namespace
# (ports 7741-7749 belong to the feature-based estimator).
if(TARGET feature_pose_estimator AND TARGET vehicle_sim AND TARGET ladar_driver AND
   EXISTS "${CMAKE_SOURCE_DIR}/tests/child_process.cc")
  add_executable(feature_bus_test feature_pose_estimator_bus_test.cc "${CMAKE_SOURCE_DIR}/tests/child_process.cc")
  target_include_directories(feature_bus_test PRIVATE "${CMAKE_SOURCE_DIR}")
  target_link_libraries(feature_bus_test PRIVATE minenav_node GTest::gtest_main)
  minenav_warnings(feature_bus_test)
  set_target_properties(feature_bus_test PROPERTIES RUNTIME_OUTPUT_DIRECTORY "${CMAKE_BINARY_DIR}/tests")
  target_compile_definitions(feature_bus_test PRIVATE
    MINENAV_FPE_BIN="$<TARGET_FILE:feature_pose_estimator>"
    MINENAV_VEHICLE_SIM_BIN="$<TARGET_FILE:vehicle_sim>"
    MINENAV_LADAR_DRIVER_BIN="$<TARGET_FILE:ladar_driver>")
  add_dependencies(feature_bus_test feature_pose_estimator vehicle_sim ladar_driver)
  add_test(NAME bus.feature_pose_estimator
    COMMAND "${CMAKE_SOURCE_DIR}/tests/bus/private_net.sh" --port 7741 -- $<TARGET_FILE:feature_bus_test>)
  set_tests_properties(bus.feature_pose_estimator PROPERTIES TIMEOUT 120 LABELS bus)
endif()
