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
