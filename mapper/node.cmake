# The mapping session (the policy batch and live share), checkpoints and the presets
# (mapper/presets/*.conf, compiled in: the installed binaries need no source tree): no LCM.
include(MinenavEmbedText)
minenav_algorithm_library(minenav_mapping_session
  ${CMAKE_CURRENT_LIST_DIR}/mapping_session.cc
  ${CMAKE_CURRENT_LIST_DIR}/map_checkpoint.cc
  ${CMAKE_CURRENT_LIST_DIR}/mapper_presets.cc)
target_link_libraries(minenav_mapping_session PUBLIC minenav_mapper)
minenav_embed_text(TARGET minenav_mapping_session HEADER mapper/mapper_presets_text.h
  NAMESPACE minenav::mapper::embedded
  FILES ${CMAKE_CURRENT_LIST_DIR}/presets/survey.conf ${CMAKE_CURRENT_LIST_DIR}/presets/carmen.conf)
minenav_test(NAME mapping_session_test NO_LCM
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/mapping_session_test.cc ${CMAKE_CURRENT_LIST_DIR}/map_checkpoint_test.cc
          ${CMAKE_CURRENT_LIST_DIR}/mapper_options_test.cc
  LIBS minenav_mapping_session)

# The contour mapper as a node (pairing, worker, answers, checkpoints, outputs), tested
# without a network through FakeBus and LogBus; the process is a thin main over it.
minenav_node_library(minenav_contour_mapper_node ${CMAKE_CURRENT_LIST_DIR}/contour_mapper_node.cc)
target_link_libraries(minenav_contour_mapper_node PUBLIC minenav_mapping_session minenav_render minenav_node)
minenav_no_ground_truth(minenav_contour_mapper_node)
minenav_test(NAME contour_mapper_node_test
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/contour_mapper_node_test.cc
  LIBS minenav_contour_mapper_node)

# The contour_mapper process: batch over logs (--log) and live.
minenav_executable(contour_mapper ${CMAKE_CURRENT_LIST_DIR}/contour_mapper_main.cc)
target_link_libraries(contour_mapper PRIVATE minenav_contour_mapper_node)

if(EXISTS "${CMAKE_SOURCE_DIR}/tests/child_process.cc")
  minenav_test(NAME contour_mapper_process_test
    SOURCES ${CMAKE_CURRENT_LIST_DIR}/contour_mapper_process_test.cc "${CMAKE_SOURCE_DIR}/tests/child_process.cc"
    LIBS minenav_mapper minenav_map_evaluation minenav_common minenav_child_process)
  target_compile_definitions(contour_mapper_process_test PRIVATE
    MINENAV_CONTOUR_MAPPER_BIN="$<TARGET_FILE:contour_mapper>" MINENAV_LOG_TOOL_BIN="$<TARGET_FILE:log_tool>")
  add_dependencies(contour_mapper_process_test contour_mapper log_tool)
endif()

# The live process on a real bus, in a private network namespace (tests/bus/private_net.sh).
if(EXISTS "${CMAKE_SOURCE_DIR}/tests/child_process.cc")
  minenav_test_program(contour_mapper_live_test
    ${CMAKE_CURRENT_LIST_DIR}/contour_mapper_live_test.cc "${CMAKE_SOURCE_DIR}/tests/child_process.cc")
  target_link_libraries(contour_mapper_live_test PRIVATE minenav_mapping_session minenav_node minenav_child_process
                        GTest::gtest_main)
  target_compile_definitions(contour_mapper_live_test PRIVATE
    MINENAV_CONTOUR_MAPPER_BIN="$<TARGET_FILE:contour_mapper>" MINENAV_LOG_TOOL_BIN="$<TARGET_FILE:log_tool>")
  add_dependencies(contour_mapper_live_test contour_mapper log_tool)
  add_test(NAME mapper.live_replay_restart_bad_input
    COMMAND "${CMAKE_SOURCE_DIR}/tests/bus/private_net.sh" --port 7760 -- $<TARGET_FILE:contour_mapper_live_test>)
  set_tests_properties(mapper.live_replay_restart_bad_input PROPERTIES TIMEOUT 900 LABELS bus)
endif()

# The live process fed faster than it maps (issue 11): a bounded queue that counts its drops,
# and a stop with a backlog that exits at once. Each test on its own port.
if(EXISTS "${CMAKE_SOURCE_DIR}/tests/child_process.cc")
  minenav_test_program(contour_mapper_live_stop_test
    ${CMAKE_CURRENT_LIST_DIR}/contour_mapper_live_stop_test.cc "${CMAKE_SOURCE_DIR}/tests/child_process.cc")
  target_link_libraries(contour_mapper_live_stop_test PRIVATE minenav_mapping_session minenav_node minenav_child_process
                        GTest::gtest_main)
  target_compile_definitions(contour_mapper_live_stop_test PRIVATE
    MINENAV_CONTOUR_MAPPER_BIN="$<TARGET_FILE:contour_mapper>")
  add_dependencies(contour_mapper_live_stop_test contour_mapper)
  add_test(NAME mapper.live_backlog_bounded
    COMMAND "${CMAKE_SOURCE_DIR}/tests/bus/private_net.sh" --port 7791 --
            $<TARGET_FILE:contour_mapper_live_stop_test> --gtest_filter=ContourMapperLiveStopTest.ABacklogIsBoundedAndEveryDropIsCounted)
  add_test(NAME mapper.live_stop_with_backlog
    COMMAND "${CMAKE_SOURCE_DIR}/tests/bus/private_net.sh" --port 7792 --
            $<TARGET_FILE:contour_mapper_live_stop_test> --gtest_filter=ContourMapperLiveStopTest.SigtermWithABacklogExitsAtOnceAndTheCheckpointKeepsTheInsertedScans)
  add_test(NAME mapper.live_kill9_loses_no_inserted_scan
    COMMAND "${CMAKE_SOURCE_DIR}/tests/bus/private_net.sh" --port 7793 --
            $<TARGET_FILE:contour_mapper_live_stop_test> --gtest_filter=ContourMapperLiveStopTest.KillNineLosesNoInsertedScan)
  set_tests_properties(mapper.live_backlog_bounded mapper.live_stop_with_backlog mapper.live_kill9_loses_no_inserted_scan
                       PROPERTIES TIMEOUT 300 LABELS bus)
endif()
