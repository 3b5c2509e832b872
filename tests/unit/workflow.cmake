# host/workflow: the local executor's pool of case threads, with stand-ins for the cases; the plugins
# the stages choose by capability; the typed
# scene, the function that sets design variables on it and the spreader's span of the width; the
# powder's size keys, with real plugins.
spreadmap_test(unit workflow SOURCES ${CMAKE_CURRENT_LIST_DIR}/workflow_local_executor_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/workflow_replicates_test.cpp ${CMAKE_CURRENT_LIST_DIR}/workflow_plugin_needs_test.cpp
  LIBS spreadmap_workflow)
# The stages' capabilities (plugin_needs): the real plugins, and the layer metrics built for ABI 10.1,
# which loads but declares no metrics.
spreadmap_older_abi_plugin(fixture_metrics_abi_10_1 KIND metrics NAME layer MINOR 1
  SOURCES ${PROJECT_SOURCE_DIR}/plugins/metrics/layer/layer.cpp LIBS layer_core)
add_dependencies(test_unit_workflow fixture_metrics_abi_10_1 plugin_metrics_layer plugin_surrogate_gp plugin_surrogate_bpnn)
target_compile_definitions(test_unit_workflow PRIVATE SPREADMAP_FIXTURE_DIR="${SPREADMAP_FIXTURE_DIR}")
spreadmap_test(unit scene_model SOURCES ${CMAKE_CURRENT_LIST_DIR}/workflow_scene_model_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/workflow_spreader_span_test.cpp ${CMAKE_CURRENT_LIST_DIR}/workflow_settle_rule_test.cpp
  LIBS spreadmap_workflow)
# Cases stepped at once in one process (the pool of --jobs) against each alone, bit for bit.
spreadmap_test(unit concurrent_cases SOURCES ${CMAKE_CURRENT_LIST_DIR}/workflow_concurrent_cases_test.cpp
  LIBS spreadmap_workflow)
add_dependencies(test_unit_concurrent_cases plugin_contact_hooke_slider plugin_spreader_roller)
spreadmap_test(unit powder SOURCES ${CMAKE_CURRENT_LIST_DIR}/workflow_powder_test.cpp LIBS spreadmap_workflow)
add_dependencies(test_unit_powder plugin_contact_hooke_slider plugin_contact_hertz_mindlin plugin_spreader_roller)
# scene.substrate.roughness: the key, its refusals, and the case set-up's fixed spheres on the plate.
# scene.substrate.height_map: its CSV file, its refusals, the substrate's tops on the map.
spreadmap_test(unit roughness SOURCES ${CMAKE_CURRENT_LIST_DIR}/workflow_roughness_test.cpp
               ${CMAKE_CURRENT_LIST_DIR}/workflow_height_map_test.cpp LIBS spreadmap_workflow)
add_dependencies(test_unit_roughness plugin_contact_hooke_slider plugin_spreader_roller)
# A scene file's block wall: the closed-form contact with its faces, edges and corners, and its motion.
spreadmap_test(unit block_wall SOURCES ${CMAKE_CURRENT_LIST_DIR}/workflow_block_wall_test.cpp LIBS spreadmap_workflow)
# scene.machine as blocks: the floor's tiling, the layers' places and the strokes.
spreadmap_test(unit machine_layout SOURCES ${CMAKE_CURRENT_LIST_DIR}/workflow_machine_layout_test.cpp
               LIBS spreadmap_workflow)
