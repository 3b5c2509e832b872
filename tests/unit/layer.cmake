# metrics/layer: the algorithm (layer_core) tested directly, the plugin through its C boundary, and
# the host's height-map writer.
if(TARGET layer_core)
  spreadmap_test(unit layer_core
    SOURCES ${CMAKE_CURRENT_LIST_DIR}/layer_clipped_sphere_test.cpp ${CMAKE_CURRENT_LIST_DIR}/layer_heightmap_test.cpp
            ${CMAKE_CURRENT_LIST_DIR}/layer_resting_test.cpp ${CMAKE_CURRENT_LIST_DIR}/layer_segregation_test.cpp
            ${CMAKE_CURRENT_LIST_DIR}/layer_substrate_test.cpp
    LIBS layer_core)
  spreadmap_test(unit layer_plugin SOURCES ${CMAKE_CURRENT_LIST_DIR}/layer_plugin_test.cpp LIBS spreadmap_sdk ${CMAKE_DL_LIBS})
  add_dependencies(test_unit_layer_plugin plugin_metrics_layer)
  target_compile_definitions(test_unit_layer_plugin PRIVATE
    SPREADMAP_LAYER_PLUGIN_FILE="$<TARGET_FILE:plugin_metrics_layer>")
endif()

if(TARGET spreadmap_core)
  spreadmap_test(unit layer_vti SOURCES ${CMAKE_CURRENT_LIST_DIR}/layer_vti_test.cpp LIBS spreadmap_core)
  find_package(VTK QUIET COMPONENTS IOXML CommonDataModel)
  if(VTK_FOUND)
    target_link_libraries(test_unit_layer_vti PRIVATE ${VTK_LIBRARIES})
    target_compile_definitions(test_unit_layer_vti PRIVATE SPREADMAP_TEST_WITH_VTK=1)
  endif()
endif()

# The effective and deposited thickness of the layers of a multi-layer bed (the characterise stage's).
if(TARGET spreadmap_workflow)
  spreadmap_test(unit layer_thickness SOURCES ${CMAKE_CURRENT_LIST_DIR}/layer_thickness_test.cpp LIBS spreadmap_workflow)
endif()
