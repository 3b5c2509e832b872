# bench_gpu (CUDA builds only): particle-steps/s of the plugins' GPU contact-force kernels at the
# peers' and the paper's scale, with the device name, beside the same stage on the CPU. Run on a GPU
# machine: build/bin/bench_gpu [--particles N ...] [--steps S] [--float].
if(NOT SPREADMAP_WITH_CUDA)
  return()
endif()
add_executable(bench_gpu ${CMAKE_CURRENT_LIST_DIR}/gpu_forces_bench.cpp)
target_link_libraries(bench_gpu PRIVATE spreadmap_cuda)
target_include_directories(bench_gpu PRIVATE ${PROJECT_SOURCE_DIR})
add_dependencies(bench_gpu plugin_contact_hooke_slider plugin_spreader_roller)

# bench_gpu_batch (CUDA builds, a GPU): the paper map's cases stepping at once on one GPU, 1, 8 and 45
# of them (bench/gpu_batch.sh runs it with the full-width scene, within 10 minutes).
add_executable(bench_gpu_batch ${CMAKE_CURRENT_LIST_DIR}/gpu_batch_bench.cpp)
target_link_libraries(bench_gpu_batch PRIVATE spreadmap_workflow)
target_include_directories(bench_gpu_batch PRIVATE ${PROJECT_SOURCE_DIR})
target_compile_definitions(bench_gpu_batch PRIVATE SPREADMAP_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
add_dependencies(bench_gpu_batch plugin_contact_hooke_slider plugin_spreader_roller)
