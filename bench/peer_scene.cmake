# bench_peer_scene: particle-steps/s of the simulate stage's spreading run on the peers' scene
# (workflows/peer_liggghts.yaml), double precision, 1 and 2 threads, beside LIGGGHTS' figure.
# bench/peer_scene.sh runs it with LIGGGHTS measured in the same run when `liggghts` is installed.
add_executable(bench_peer_scene ${CMAKE_CURRENT_LIST_DIR}/peer_scene_bench.cpp)
target_link_libraries(bench_peer_scene PRIVATE spreadmap_workflow)
target_include_directories(bench_peer_scene PRIVATE ${PROJECT_SOURCE_DIR})
target_compile_definitions(bench_peer_scene PRIVATE SPREADMAP_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
add_dependencies(bench_peer_scene plugin_contact_hooke_slider plugin_spreader_roller)
