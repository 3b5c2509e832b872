# Backend comparisons that need a CUDA device (label gpu: CI leaves it out when no GPU is present and
# says so). Built only with CUDA; each test skips, saying why, on a machine without a usable device.
if(NOT SPREADMAP_WITH_CUDA)
  return()
endif()
spreadmap_test(gpu contact_backends
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/contact_backends_test.cpp
  LIBS spreadmap_cuda)
add_dependencies(test_gpu_contact_backends ${spreadmap_contact_plugins} plugin_spreader_roller plugin_spreader_blade)
spreadmap_test(gpu engine_backends
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/engine_backends_test.cpp
  LIBS spreadmap_workflow spreadmap_cuda)
add_dependencies(test_gpu_engine_backends plugin_contact_hooke_slider plugin_spreader_roller)
spreadmap_test(gpu engine_batch
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/engine_batch_test.cpp
  LIBS spreadmap_workflow spreadmap_cuda)
add_dependencies(test_gpu_engine_batch plugin_contact_hooke_slider plugin_spreader_roller)
