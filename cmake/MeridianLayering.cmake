# The layers of docs/architecture.md, enforced on the target graph (at configure time) and on
# the sources' #include lines (tests/layering, a CTest case).
#
#   numerics   core adjust geodesy filter gravity gyro maglev dov nav: may use numerics only
#   io         io, io_<wf>: readers, writers of input files, runners; may use numerics and io
#   report     report, report_<wf>: writers of results; may use numerics and report, never io
#   front ends apps/meridian (the CLI) and python/ (the package): may use all, but never
#              nlohmann-json or yaml-cpp themselves (they call writers and runners)
#
# A forbidden dependency stops the configuration with a message naming both ends, so it cannot
# be built, and the source check fails the test suite.

set(MERIDIAN_NUMERICS_MODULES core adjust geodesy filter gravity gyro maglev dov nav)

# meridian_layer_of(<module name without meridian_> <out var>): numerics, io or report.
function(meridian_layer_of module out)
  if(module STREQUAL "io" OR module MATCHES "^io_")
    set(${out} io PARENT_SCOPE)
  elseif(module STREQUAL "report" OR module MATCHES "^report_")
    set(${out} report PARENT_SCOPE)
  else()
    set(${out} numerics PARENT_SCOPE)
  endif()
endfunction()

# meridian_layering_violation(<from layer> <to layer> <out var>): the rule broken, or empty.
function(meridian_layering_violation from to out)
  set(v "")
  if(from STREQUAL "numerics" AND NOT to STREQUAL "numerics")
    set(v "numerics modules may not use ${to} (numerics never read, write or format)")
  elseif(from STREQUAL "report" AND to STREQUAL "io")
    set(v "report modules may not use io (writers take a Result, not a file)")
  elseif(from STREQUAL "io" AND to STREQUAL "report")
    set(v "io modules may not use report (runners return Results; writers are the report's)")
  endif()
  set(${out} "${v}" PARENT_SCOPE)
endfunction()

# The Meridian module a link item names (Meridian::x, meridian_x, $<LINK_ONLY:…>), or empty.
function(_meridian_module_of_item item out)
  set(m "")
  if(item MATCHES "^\\$<LINK_ONLY:(.*)>$")
    set(item "${CMAKE_MATCH_1}")
  endif()
  if(item MATCHES "^Meridian::([a-z_0-9]+)$")
    set(m "${CMAKE_MATCH_1}")
  elseif(item MATCHES "^meridian_([a-z_0-9]+)$")
    set(m "${CMAKE_MATCH_1}")
  endif()
  set(${out} "${m}" PARENT_SCOPE)
endfunction()

# meridian_check_layering(FRONT_ENDS target…): every module's links against the layers, and the
# front ends' direct links against nlohmann-json and yaml-cpp. Call after all targets exist.
function(meridian_check_layering)
  cmake_parse_arguments(L "" "" "FRONT_ENDS" ${ARGN})
  get_property(modules GLOBAL PROPERTY MERIDIAN_MODULES)
  set(problems "")
  foreach(t ${modules})
    string(REGEX REPLACE "^meridian_" "" from "${t}")
    meridian_layer_of(${from} from_layer)
    get_target_property(links ${t} LINK_LIBRARIES)
    get_target_property(ilinks ${t} INTERFACE_LINK_LIBRARIES)
    foreach(item IN LISTS links ilinks)
      _meridian_module_of_item("${item}" to)
      if(to STREQUAL "" OR to STREQUAL from)
        continue()
      endif()
      meridian_layer_of(${to} to_layer)
      meridian_layering_violation(${from_layer} ${to_layer} why)
      if(why)
        list(APPEND problems "Meridian::${from} links Meridian::${to}: ${why}")
      endif()
    endforeach()
  endforeach()
  foreach(t ${L_FRONT_ENDS})
    if(NOT TARGET ${t})
      continue()
    endif()
    get_target_property(links ${t} LINK_LIBRARIES)
    foreach(item IN LISTS links)
      if(item MATCHES "nlohmann_json|yaml-cpp|yaml_cpp")
        list(APPEND problems "${t} links ${item}: front ends call writers and runners, they do not build JSON or YAML")
      endif()
    endforeach()
  endforeach()
  if(problems)
    list(JOIN problems "\n  " text)
    message(FATAL_ERROR "Layering (docs/architecture.md, cmake/MeridianLayering.cmake) broken:\n  ${text}")
  endif()
endfunction()
