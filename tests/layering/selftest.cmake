# cmake -DSOURCE_DIR=<meridian source> -DWORK=<scratch folder> -P selftest.cmake
# Shows that both layering checks fail when a forbidden dependency appears: a tree with one
# bad #include per rule for check_includes.cmake, and a project whose module links a
# forbidden module for meridian_check_layering (cmake/MeridianLayering.cmake). A clean tree and
# a clean project must pass, so the checks are not failing on everything.
file(REMOVE_RECURSE "${WORK}")
set(cases
  "src/gyro/x.cpp|#include \"meridian/io/gyro_files.hpp\""
  "include/meridian/nav/x.hpp|#include \"meridian/report/nav_html.hpp\""
  "src/report/x.cpp|#include \"meridian/io/nmea.hpp\""
  "src/io/x.cpp|#include \"meridian/report/html.hpp\""
  "apps/meridian/x.cpp|#include <nlohmann/json.hpp>"
  "python/src/x.cpp|  #  include <yaml-cpp/yaml.h>"
  "apps/meridian/x.cpp|  const auto j = nlohmann::json::array()")
set(i 0)
foreach(c ${cases})
  string(REPLACE "|" ";" parts "${c}")
  list(GET parts 0 path)
  list(GET parts 1 line)
  set(tree "${WORK}/bad${i}")
  file(WRITE "${tree}/src/gyro/fine.cpp" "#include \"meridian/gyro/reduce.hpp\"\n")
  file(WRITE "${tree}/${path}" "// a line\n${line}\n")
  execute_process(COMMAND "${CMAKE_COMMAND}" -DROOT=${tree} -P "${SOURCE_DIR}/tests/layering/check_includes.cmake"
                  RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
  if(rc EQUAL 0)
    message(FATAL_ERROR "check_includes.cmake passed a tree with ${path}: ${line}")
  endif()
  if(NOT err MATCHES "${path}:")
    message(FATAL_ERROR "check_includes.cmake did not name ${path}:2 for ${line}:\n${err}")
  endif()
  math(EXPR i "${i} + 1")
endforeach()
file(WRITE "${WORK}/good/src/gyro/fine.cpp" "#include \"meridian/gyro/reduce.hpp\"\n")
file(WRITE "${WORK}/good/apps/meridian/fine.cpp" "#include \"meridian/report/json_text.hpp\"\n")
execute_process(COMMAND "${CMAKE_COMMAND}" -DROOT=${WORK}/good -P "${SOURCE_DIR}/tests/layering/check_includes.cmake"
                RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "check_includes.cmake failed a clean tree:\n${err}")
endif()

# The target graph: a numerics module linking an io module, a report module linking io, a
# front end linking nlohmann-json; then a clean graph.
foreach(variant numerics_io report_io front_json clean)
  set(p "${WORK}/project_${variant}")
  set(links_gyro "")
  set(links_report "meridian_gyro")
  set(links_front "meridian_report_gyro")
  if(variant STREQUAL "numerics_io")
    set(links_gyro "Meridian::io_gyro")
  elseif(variant STREQUAL "report_io")
    set(links_report "meridian_gyro;$<LINK_ONLY:meridian_io_gyro>")
  elseif(variant STREQUAL "front_json")
    set(links_front "meridian_report_gyro;nlohmann_json::nlohmann_json")
  endif()
  file(WRITE "${p}/CMakeLists.txt" "
cmake_minimum_required(VERSION 3.25)
project(layering_fixture NONE)
include(\"${SOURCE_DIR}/cmake/MeridianLayering.cmake\")
function(module name)
  add_library(meridian_\${name} INTERFACE)
  add_library(Meridian::\${name} ALIAS meridian_\${name})
  set_property(GLOBAL APPEND PROPERTY MERIDIAN_MODULES meridian_\${name})
endfunction()
module(io_gyro)
module(gyro)
module(report_gyro)
target_link_libraries(meridian_gyro INTERFACE ${links_gyro})
target_link_libraries(meridian_report_gyro INTERFACE ${links_report})
add_library(nlohmann_json::nlohmann_json INTERFACE IMPORTED)
add_custom_target(front)
set_property(TARGET front PROPERTY LINK_LIBRARIES \"${links_front}\")
meridian_check_layering(FRONT_ENDS front)
")
  execute_process(COMMAND "${CMAKE_COMMAND}" -S "${p}" -B "${p}/build" RESULT_VARIABLE rc
                  OUTPUT_QUIET ERROR_VARIABLE err)
  if(variant STREQUAL "clean")
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "meridian_check_layering failed a clean graph:\n${err}")
    endif()
  elseif(rc EQUAL 0 OR NOT err MATCHES "Layering")
    message(FATAL_ERROR "meridian_check_layering passed the graph '${variant}':\n${err}")
  endif()
endforeach()
message(STATUS "layering self-test: every forbidden dependency was refused, the clean ones passed")
