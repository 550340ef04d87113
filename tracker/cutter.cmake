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
# cutterhead (sim/), the ladar ray cast and the contour mapper's live changing-world map.
if(TARGET minenav_mapper)
  minenav_test(NAME cutter_sim_test NO_LCM SOURCES cutter_sim_test.cc TIMEOUT 900
    LIBS minenav_cutter minenav_sim minenav_mapper)
endif()
