# The cutter (thesis 6.4.1): its library (no LCM, no clock, no simulator), the appendage
# messages' LCM conversions (also used by vehicle_sim), the node and the process.
minenav_algorithm_library(minenav_cutter cutter.cc)
target_link_libraries(minenav_cutter PUBLIC minenav_common)
minenav_no_ground_truth(minenav_cutter)

minenav_node_library(minenav_cutter_messages cutter_conversions.cc)
target_link_libraries(minenav_cutter_messages PUBLIC minenav_common minenav_node)

minenav_node_library(minenav_cutter_node cutter_node.cc)
target_link_libraries(minenav_cutter_node PUBLIC minenav_cutter minenav_cutter_messages minenav_node)
minenav_no_ground_truth(minenav_cutter_node)

minenav_executable(cutter cutter_main.cc)
target_link_libraries(cutter PRIVATE minenav_cutter_node)
minenav_no_ground_truth(cutter)
minenav_check_links_no_ground_truth(minenav_cutter minenav_cutter_node cutter)

minenav_test(NAME cutter_test NO_LCM SOURCES cutter_test.cc LIBS minenav_cutter)
minenav_test(NAME cutter_node_test SOURCES cutter_node_test.cc LIBS minenav_cutter_node)
# The sump-shear cycle closed in simulation: the cutter library, the simulated miner and
# cutterhead (sim/), the simulated ladar and the live contour mapper's changing-world map
# (the tracker's simulation harness: testing/mapper_pose_source.h).
if(TARGET minenav_mapper)
  minenav_test(NAME cutter_sim_test NO_LCM SOURCES cutter_sim_test.cc TIMEOUT 1800
    LIBS minenav_cutter minenav_tracker_sim_harness)
endif()

# Live on the bus (tests/bus/private_net.sh, port 7820): vehicle_sim + ladar_driver +
# contour_mapper + cutter.
if(TARGET vehicle_sim AND TARGET ladar_driver AND TARGET contour_mapper)
  minenav_test_program(cutter_bus_test cutter_bus_test.cc)
  target_link_libraries(cutter_bus_test PRIVATE minenav_test_support minenav_node GTest::gtest_main)
  target_compile_definitions(cutter_bus_test PRIVATE
    MINENAV_VEHICLE_SIM_BIN="$<TARGET_FILE:vehicle_sim>" MINENAV_LADAR_DRIVER_BIN="$<TARGET_FILE:ladar_driver>"
    MINENAV_CONTOUR_MAPPER_BIN="$<TARGET_FILE:contour_mapper>" MINENAV_CUTTER_BIN="$<TARGET_FILE:cutter>")
  add_dependencies(cutter_bus_test vehicle_sim ladar_driver contour_mapper cutter)
  add_test(NAME bus.cutter_box_cut
    COMMAND "${CMAKE_SOURCE_DIR}/tests/bus/private_net.sh" --port 7820 -- $<TARGET_FILE:cutter_bus_test>)
  set_tests_properties(bus.cutter_box_cut PROPERTIES TIMEOUT 300 LABELS bus)
endif()
