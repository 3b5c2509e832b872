# bench_render: a 235,000-particle snapshot at 1920x1080 (prints time and core count).
if(TARGET spreadmap_render)
  add_executable(bench_render ${CMAKE_CURRENT_LIST_DIR}/render_bench.cpp)
  target_link_libraries(bench_render PRIVATE spreadmap_render)
endif()
