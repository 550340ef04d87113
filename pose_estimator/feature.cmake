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
