# The host-device loop bodies run on the CPU, and the backend choice: in every build. With CUDA in the
# build, also that every contact and spreader plugin carries its GPU kernels (tests/gpu compares the
# numbers where a device exists).
spreadmap_test(unit cuda_loops
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/cuda_loops_test.cpp
  LIBS spreadmap_sdk)
spreadmap_test(unit cuda_backend
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/cuda_backend_test.cpp
  LIBS spreadmap_backend)
if(NOT SPREADMAP_WITH_CUDA)
  return()
endif()
# A contact module built without spreadmap_add_plugin()'s CUDA hook, as a CPU-only build makes it.
add_library(test_cuda_cpu_only_spring MODULE ${CMAKE_CURRENT_LIST_DIR}/cuda_cpu_only_law.cpp)
target_link_libraries(test_cuda_cpu_only_spring PRIVATE spreadmap_sdk)
set_target_properties(test_cuda_cpu_only_spring PROPERTIES PREFIX "" OUTPUT_NAME cpu_only_spring
  CXX_VISIBILITY_PRESET hidden VISIBILITY_INLINES_HIDDEN ON
  LIBRARY_OUTPUT_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}/cuda_modules/contact)
spreadmap_test(unit cuda_plugins
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/cuda_plugins_test.cpp
  LIBS spreadmap_cuda)
target_compile_definitions(test_unit_cuda_plugins PRIVATE
  SPREADMAP_CPU_ONLY_MODULE="${CMAKE_CURRENT_BINARY_DIR}/cuda_modules/contact/cpu_only_spring.so")
add_dependencies(test_unit_cuda_plugins test_cuda_cpu_only_spring ${spreadmap_contact_plugins}
                 plugin_spreader_roller plugin_spreader_blade)
