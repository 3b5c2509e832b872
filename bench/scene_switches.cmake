# bench_scene_switches: the saving of each "only what a scene requires" switch (sleeping particles,
# rotation skipped without torque, walls absent) on the quickstart's scene, and its effect on V_s
# and R_q against the heap-to-heap scatter.
add_executable(bench_scene_switches ${CMAKE_CURRENT_LIST_DIR}/scene_switches_bench.cpp)
target_link_libraries(bench_scene_switches PRIVATE spreadmap_workflow)
target_compile_definitions(bench_scene_switches PRIVATE SPREADMAP_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
add_dependencies(bench_scene_switches plugin_contact_hooke_slider plugin_spreader_roller plugin_metrics_layer)
