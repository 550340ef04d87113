# Processes of sim/ (owned by the node author): thin nodes over minenav_sim.
minenav_executable(vehicle_sim vehicle_sim_main.cc)
target_link_libraries(vehicle_sim PRIVATE minenav_sim minenav_node)
