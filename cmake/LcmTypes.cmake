# Finds LCM 1.3.1 as Debian ships it (no CMake config; its pkg-config file needs glib's,
# which liblcm-dev does not pull in) and turns .lcm files into C++ headers.

find_path(LCM_INCLUDE_DIR lcm/lcm-cpp.hpp REQUIRED)
find_library(LCM_LIBRARY lcm REQUIRED)
find_program(LCM_GEN lcm-gen REQUIRED)
if(NOT TARGET lcm::lcm)
  add_library(lcm::lcm UNKNOWN IMPORTED)
  set_target_properties(lcm::lcm PROPERTIES
    IMPORTED_LOCATION "${LCM_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${LCM_INCLUDE_DIR}")
endif()

# minenav_lcm_types(TARGET <name> FILES a.lcm b.lcm ...)
# One add_custom_command per .lcm file, so editing one type regenerates just its header
# and rebuilds what includes it. The result is an INTERFACE target whose include
# directory is SYSTEM: generated code does not trip our strict warnings.
function(minenav_lcm_types)
  cmake_parse_arguments(ARG "" "TARGET" "FILES" ${ARGN})
  set(out_dir "${CMAKE_CURRENT_BINARY_DIR}/lcmtypes_cpp")
  set(headers)
  foreach(lcm_file IN LISTS ARG_FILES)
    get_filename_component(abs "${lcm_file}" ABSOLUTE)
    get_filename_component(stem "${lcm_file}" NAME_WE)
    set(header "${out_dir}/minenav/${stem}.hpp")
    add_custom_command(
      OUTPUT "${header}"
      COMMAND "${LCM_GEN}" --cpp --cpp-std c++11 --cpp-hpath "${out_dir}" "${abs}"
      DEPENDS "${abs}"
      COMMENT "lcm-gen ${stem}.lcm"
      VERBATIM)
    list(APPEND headers "${header}")
    file(WRITE "${CMAKE_BINARY_DIR}/no_lcm/minenav/${stem}.hpp"
      "#error \"LCM message type in an algorithm library: convert in the node (common/node/conversions.h).\"\n")
  endforeach()
  # One more header from all the types: the pre-decode wire check (cmake/lcm_wire_check.py).
  find_package(Python3 REQUIRED COMPONENTS Interpreter)
  set(abs_files)
  foreach(lcm_file IN LISTS ARG_FILES)
    get_filename_component(abs "${lcm_file}" ABSOLUTE)
    list(APPEND abs_files "${abs}")
  endforeach()
  set(wire_check "${out_dir}/minenav/wire_check.hpp")
  add_custom_command(
    OUTPUT "${wire_check}"
    COMMAND Python3::Interpreter "${CMAKE_SOURCE_DIR}/cmake/lcm_wire_check.py" "${wire_check}" ${abs_files}
    DEPENDS ${abs_files} "${CMAKE_SOURCE_DIR}/cmake/lcm_wire_check.py"
    COMMENT "lcm_wire_check.py: minenav/wire_check.hpp"
    VERBATIM)
  list(APPEND headers "${wire_check}")
  file(WRITE "${CMAKE_BINARY_DIR}/no_lcm/minenav/wire_check.hpp"
    "#error \"LCM message type in an algorithm library: convert in the node (common/node/conversions.h).\"\n")
  add_custom_target(${ARG_TARGET}_gen DEPENDS ${headers})
  add_library(${ARG_TARGET} INTERFACE)
  add_dependencies(${ARG_TARGET} ${ARG_TARGET}_gen)
  target_include_directories(${ARG_TARGET} SYSTEM INTERFACE "${out_dir}")
  target_link_libraries(${ARG_TARGET} INTERFACE lcm::lcm)
  # lcm-gen's decode() reads the fingerprint into an uninitialised local that GCC's
  # middle end flags after inlining; SYSTEM does not silence middle-end warnings.
  # (A GCC-only option: clang, which the fuzz build uses, does not know it.)
  target_compile_options(${ARG_TARGET} INTERFACE $<$<CXX_COMPILER_ID:GNU>:-Wno-maybe-uninitialized>)
endfunction()

# minenav_lcm_json(TARGET <name> TYPES <lcm types target> FILES a.lcm ...)
# minenav/message_json.hpp (cmake/lcm_json.py): every type's JSON form and JSON Schema, for
# the tools that show messages to people (viewer/, logger/'s MCAP export and spy). An
# INTERFACE target of its own, so that only they depend on nlohmann::json.
function(minenav_lcm_json)
  cmake_parse_arguments(ARG "" "TARGET;TYPES" "FILES" ${ARGN})
  set(out_dir "${CMAKE_CURRENT_BINARY_DIR}/lcmtypes_json")
  set(header "${out_dir}/minenav/message_json.hpp")
  set(abs_files)
  foreach(lcm_file IN LISTS ARG_FILES)
    get_filename_component(abs "${lcm_file}" ABSOLUTE)
    list(APPEND abs_files "${abs}")
  endforeach()
  add_custom_command(
    OUTPUT "${header}"
    COMMAND Python3::Interpreter "${CMAKE_SOURCE_DIR}/cmake/lcm_json.py" "${header}" ${abs_files}
    DEPENDS ${abs_files} "${CMAKE_SOURCE_DIR}/cmake/lcm_json.py" "${CMAKE_SOURCE_DIR}/cmake/lcm_wire_check.py"
    COMMENT "lcm_json.py: minenav/message_json.hpp"
    VERBATIM)
  file(WRITE "${CMAKE_BINARY_DIR}/no_lcm/minenav/message_json.hpp"
    "#error \"LCM message type in an algorithm library: convert in the node (common/node/conversions.h).\"\n")
  add_custom_target(${ARG_TARGET}_gen DEPENDS "${header}")
  add_library(${ARG_TARGET} INTERFACE)
  add_dependencies(${ARG_TARGET} ${ARG_TARGET}_gen)
  target_include_directories(${ARG_TARGET} SYSTEM INTERFACE "${out_dir}")
  target_link_libraries(${ARG_TARGET} INTERFACE ${ARG_TYPES} nlohmann_json::nlohmann_json)
endfunction()
