# metrics/layer: the algorithm (layer_core) tested directly, and the plugin through its C boundary.
spreadmap_test(unit layer_core
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/layer_clipped_sphere_test.cpp ${CMAKE_CURRENT_LIST_DIR}/layer_heightmap_test.cpp
          ${CMAKE_CURRENT_LIST_DIR}/layer_resting_test.cpp ${CMAKE_CURRENT_LIST_DIR}/layer_segregation_test.cpp
          ${CMAKE_CURRENT_LIST_DIR}/layer_substrate_test.cpp
  LIBS layer_core)
spreadmap_test(unit layer_plugin SOURCES ${CMAKE_CURRENT_LIST_DIR}/layer_plugin_test.cpp LIBS spreadmap_sdk ${CMAKE_DL_LIBS})
add_dependencies(test_unit_layer_plugin plugin_metrics_layer)
target_compile_definitions(test_unit_layer_plugin PRIVATE
  SPREADMAP_LAYER_PLUGIN_FILE="$<TARGET_FILE:plugin_metrics_layer>")
