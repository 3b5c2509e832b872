# spreadmap_add_plugin(KIND <contact|spreader|metrics|surrogate> NAME <name> [CPU_ONLY] SOURCES <files...>)
# Builds one plugin as a MODULE named <name>.so that links only the SDK (headers), with hidden
# visibility so that `spreadmap_plugin_v1` is its only exported symbol. In the source tree it lands
# in <build>/lib/spreadmap/plugins/<kind>/, beside the binary's ../lib, exactly as an install does.
# CPU_ONLY: no GPU kernels (a plugin whose data lives in host memory, such as a triangle mesh).
include(${CMAKE_CURRENT_LIST_DIR}/SpreadmapWarnings.cmake)
function(spreadmap_add_plugin)
  cmake_parse_arguments(P "CPU_ONLY" "KIND;NAME" "SOURCES" ${ARGN})
  if(NOT P_KIND MATCHES "^(contact|spreader|metrics|surrogate)$")
    message(FATAL_ERROR "spreadmap_add_plugin: KIND must be contact, spreader, metrics or surrogate, not '${P_KIND}'")
  endif()
  set(t plugin_${P_KIND}_${P_NAME})
  add_library(${t} MODULE ${P_SOURCES})
  target_compile_options(${t} PRIVATE ${SPREADMAP_WARNING_OPTIONS})
  if(TARGET spreadmap_sdk)
    target_link_libraries(${t} PRIVATE spreadmap_sdk)
  else()
    target_link_libraries(${t} PRIVATE spreadmap::sdk)
  endif()
  if(DEFINED SPREADMAP_PLUGIN_DIR)
    set(out ${SPREADMAP_PLUGIN_DIR}/${P_KIND})
  else()
    set(out ${CMAKE_BINARY_DIR}/lib/spreadmap/plugins/${P_KIND})
  endif()
  set_target_properties(${t} PROPERTIES PREFIX "" OUTPUT_NAME ${P_NAME}
    CXX_VISIBILITY_PRESET hidden VISIBILITY_INLINES_HIDDEN ON
    LIBRARY_OUTPUT_DIRECTORY ${out})
  if(COMMAND spreadmap_plugin_cuda AND NOT P_CPU_ONLY)
    spreadmap_plugin_cuda(${t} ${P_KIND} "${P_SOURCES}")
  endif()
  # Literally lib/, not CMAKE_INSTALL_LIBDIR (lib/x86_64-linux-gnu under /usr on Debian): the binary
  # looks in <its folder>/../lib/spreadmap/plugins.
  install(TARGETS ${t} LIBRARY DESTINATION lib/spreadmap/plugins/${P_KIND})
  # every plugin, for the `programs` target (the program and its plugins: what the quickstart builds)
  set_property(GLOBAL APPEND PROPERTY SPREADMAP_PLUGIN_TARGETS ${t})
endfunction()
