# Processes of sensor_driver/ (owned by the node author): thin nodes over minenav_ladar.
minenav_executable(ladar_driver ladar_driver_main.cc)
target_link_libraries(ladar_driver PRIVATE minenav_ladar minenav_node)
