# bench_layer: characterisation time of a paper-sized layer (see layer_bench.cpp).
if(TARGET layer_core)
  add_executable(bench_layer ${CMAKE_CURRENT_LIST_DIR}/layer_bench.cpp)
  target_link_libraries(bench_layer PRIVATE layer_core)
endif()
