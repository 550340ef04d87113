# Iconic pose estimator (thesis chapter 3, App. A.2-A.3): library, tests, process.
minenav_algorithm_library(minenav_iconic
  ${CMAKE_CURRENT_LIST_DIR}/correspondence.cc
  ${CMAKE_CURRENT_LIST_DIR}/grid_search_correspondence.cc
  ${CMAKE_CURRENT_LIST_DIR}/iconic_estimator.cc
  ${CMAKE_CURRENT_LIST_DIR}/iconic_matcher.cc
  ${CMAKE_CURRENT_LIST_DIR}/iconic_residual.cc
  ${CMAKE_CURRENT_LIST_DIR}/lookup_table_correspondence.cc
  ${CMAKE_CURRENT_LIST_DIR}/multi_scan_matcher.cc
  ${CMAKE_CURRENT_LIST_DIR}/scan_polylines.cc
  ${CMAKE_CURRENT_LIST_DIR}/scan_set_map.cc
  ${CMAKE_CURRENT_LIST_DIR}/segment_map.cc)
target_link_libraries(minenav_iconic PUBLIC minenav_common Eigen3::Eigen)

minenav_test(NAME iconic_test NO_LCM
  SOURCES
    ${CMAKE_CURRENT_LIST_DIR}/correspondence_test.cc
    ${CMAKE_CURRENT_LIST_DIR}/iconic_residual_test.cc
    ${CMAKE_CURRENT_LIST_DIR}/iconic_matcher_test.cc
    ${CMAKE_CURRENT_LIST_DIR}/multi_scan_matcher_test.cc
    ${CMAKE_CURRENT_LIST_DIR}/iconic_estimator_test.cc
    ${CMAKE_CURRENT_LIST_DIR}/scan_polylines_test.cc
    ${CMAKE_CURRENT_LIST_DIR}/iconic_test_world.cc
  LIBS minenav_iconic)

# The process: live on the bus, or batch over a log (--log) writing a poses CSV.
if(TARGET minenav_node)
  minenav_executable(iconic_pose_estimator ${CMAKE_CURRENT_LIST_DIR}/iconic_pose_estimator_main.cc)
  target_link_libraries(iconic_pose_estimator PRIVATE minenav_iconic minenav_node ZLIB::ZLIB)
endif()

# The process in batch (no bus): a log in, poses out, every mode, bad input.
if(TARGET iconic_pose_estimator AND EXISTS "${CMAKE_SOURCE_DIR}/tests/child_process.cc")
  minenav_test(NAME iconic_process_test
    SOURCES ${CMAKE_CURRENT_LIST_DIR}/iconic_process_test.cc ${CMAKE_CURRENT_LIST_DIR}/iconic_test_world.cc
            "${CMAKE_SOURCE_DIR}/tests/child_process.cc"
    LIBS minenav_iconic minenav_node)
  target_compile_definitions(iconic_process_test PRIVATE MINENAV_IPE_BIN="$<TARGET_FILE:iconic_pose_estimator>")
  add_dependencies(iconic_process_test iconic_pose_estimator)
endif()

# On the bus (private network namespace, port 7731): vehicle_sim + ladar_driver +
# iconic_pose_estimator with the world as the surveyed map; POSE_IPE tracks SIM_TRUTH.
if(TARGET iconic_pose_estimator AND TARGET vehicle_sim AND TARGET ladar_driver
   AND EXISTS "${CMAKE_SOURCE_DIR}/tests/child_process.cc")
  add_executable(iconic_bus_test ${CMAKE_CURRENT_LIST_DIR}/iconic_bus_test.cc "${CMAKE_SOURCE_DIR}/tests/child_process.cc")
  target_include_directories(iconic_bus_test PRIVATE "${CMAKE_SOURCE_DIR}")
  target_link_libraries(iconic_bus_test PRIVATE minenav_node GTest::gtest_main)
  target_compile_definitions(iconic_bus_test PRIVATE
    MINENAV_IPE_BIN="$<TARGET_FILE:iconic_pose_estimator>"
    MINENAV_VEHICLE_SIM_BIN="$<TARGET_FILE:vehicle_sim>"
    MINENAV_LADAR_DRIVER_BIN="$<TARGET_FILE:ladar_driver>")
  minenav_warnings(iconic_bus_test)
  set_target_properties(iconic_bus_test PROPERTIES RUNTIME_OUTPUT_DIRECTORY "${CMAKE_BINARY_DIR}/tests")
  add_dependencies(iconic_bus_test iconic_pose_estimator vehicle_sim ladar_driver)
  add_test(NAME ipe.bus_tracks_truth
    COMMAND "${CMAKE_SOURCE_DIR}/tests/bus/private_net.sh" --port 7731 -- $<TARGET_FILE:iconic_bus_test>)
  set_tests_properties(ipe.bus_tracks_truth PROPERTIES TIMEOUT 180 LABELS bus)
endif()
