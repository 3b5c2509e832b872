# bench_machine_peaks: this processor's clock, floating-point peaks (fused and not, 128 to 512-bit,
# double and float) and read bandwidth per cache level, for docs/performance.md's limit table.
if(CMAKE_SYSTEM_PROCESSOR MATCHES "x86_64|AMD64")  # x86 intrinsics
  add_executable(bench_machine_peaks ${CMAKE_CURRENT_LIST_DIR}/machine_peaks_bench.cpp)
  target_link_libraries(bench_machine_peaks PRIVATE OpenMP::OpenMP_CXX)
  target_compile_options(bench_machine_peaks PRIVATE -O2 -ffp-contract=off)  # a multiply and an add stay two
endif()
