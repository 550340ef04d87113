# Processes of sensor_driver/ (owned by the node author): thin mains over their nodes (LCM)
# over minenav_ladar.
minenav_node_library(minenav_ladar_node ladar_driver_node.cc)
target_link_libraries(minenav_ladar_node PUBLIC minenav_ladar minenav_node)

minenav_executable(ladar_driver ladar_driver_main.cc)
target_link_libraries(ladar_driver PRIVATE minenav_ladar_node)

minenav_test(NAME ladar_driver_node_test SOURCES ladar_driver_node_test.cc LIBS minenav_ladar_node)
