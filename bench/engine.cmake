# bench_engine: engine throughput (particle-steps/s) on a settling and shaken box of ~20,000 spheres,
# double and float, 1 and 2 threads (see engine_bench.cpp).
add_executable(bench_engine ${CMAKE_CURRENT_LIST_DIR}/engine_bench.cpp)
target_link_libraries(bench_engine PRIVATE spreadmap_engine)
target_include_directories(bench_engine PRIVATE ${PROJECT_SOURCE_DIR})
