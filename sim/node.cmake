# Processes of sim/ (owned by the node author): thin mains over their nodes (LCM) over
# minenav_sim.
minenav_node_library(minenav_vehicle_sim_node vehicle_sim_node.cc)
target_link_libraries(minenav_vehicle_sim_node PUBLIC minenav_sim minenav_node minenav_cutter_messages)

minenav_executable(vehicle_sim vehicle_sim_main.cc)
target_link_libraries(vehicle_sim PRIVATE minenav_vehicle_sim_node)

minenav_test(NAME vehicle_sim_node_test SOURCES vehicle_sim_node_test.cc LIBS minenav_vehicle_sim_node)
