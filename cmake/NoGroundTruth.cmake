# Ground truth stays out of everything that decides where the vehicle is or how it moves
# (DESIGN.md: SIM_TRUTH feeds the ladar simulation and evaluation only). Two checks, like
# the LCM guard:
#  - minenav_no_ground_truth(target): `#include "sim/..."` or "sensor_driver/..." in the
#    target's own sources fails to compile (poison headers first on its include path);
#  - minenav_check_links_no_ground_truth(targets...), run once every target exists: none of
#    them may link the simulator's libraries, directly or through another library.

set(MINENAV_GROUND_TRUTH_LIBRARIES minenav_sim minenav_survey minenav_ladar)
set(MINENAV_NO_GROUND_TRUTH_DIR "${CMAKE_BINARY_DIR}/no_ground_truth")

file(GLOB _minenav_truth_headers RELATIVE "${CMAKE_SOURCE_DIR}"
     "${CMAKE_SOURCE_DIR}/sim/*.h" "${CMAKE_SOURCE_DIR}/sensor_driver/*.h")
foreach(header IN LISTS _minenav_truth_headers)
  file(WRITE "${MINENAV_NO_GROUND_TRUTH_DIR}/${header}"
       "#error \"ground truth (the simulator) in an estimator, mapper, planner or tracker: see cmake/NoGroundTruth.cmake\"\n")
endforeach()

function(minenav_no_ground_truth target)
  target_include_directories(${target} BEFORE PRIVATE "${MINENAV_NO_GROUND_TRUTH_DIR}")
endfunction()

# Every library `target` links, directly or not (targets only).
function(_minenav_link_closure target out)
  set(seen "")
  set(todo "${target}")
  while(todo)
    list(POP_FRONT todo t)
    if(NOT TARGET ${t} OR t IN_LIST seen)
      continue()
    endif()
    list(APPEND seen ${t})
    get_target_property(type ${t} TYPE)
    set(props INTERFACE_LINK_LIBRARIES)
    if(NOT type STREQUAL "INTERFACE_LIBRARY")
      list(APPEND props LINK_LIBRARIES)
    endif()
    foreach(p IN LISTS props)
      get_target_property(libs ${t} ${p})
      if(libs)
        foreach(l IN LISTS libs)
          string(REGEX REPLACE "^\\$<LINK_ONLY:(.*)>$" "\\1" l "${l}")
          list(APPEND todo ${l})
        endforeach()
      endif()
    endforeach()
  endwhile()
  set(${out} "${seen}" PARENT_SCOPE)
endfunction()

function(minenav_check_links_no_ground_truth)
  foreach(target IN LISTS ARGN)
    if(NOT TARGET ${target})
      continue()
    endif()
    _minenav_link_closure(${target} closure)
    foreach(forbidden IN LISTS MINENAV_GROUND_TRUTH_LIBRARIES)
      if(forbidden IN_LIST closure)
        message(FATAL_ERROR " ${target} links ${forbidden}: estimators, the mapper, planners and trackers "
                "must never see ground truth (cmake/NoGroundTruth.cmake)")
      endif()
    endforeach()
  endforeach()
endfunction()
