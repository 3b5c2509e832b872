# The host's height-map writer and the layers' thickness (the metrics/layer plugin's own tests are in
# its folder, plugins/metrics/layer/tests.cmake).
if(TARGET spreadmap_core)
  spreadmap_test(unit layer_vti SOURCES ${CMAKE_CURRENT_LIST_DIR}/layer_vti_test.cpp LIBS spreadmap_core)
  find_package(VTK QUIET COMPONENTS IOXML CommonDataModel)
  if(VTK_FOUND)
    target_link_libraries(test_unit_layer_vti PRIVATE ${VTK_LIBRARIES})
    target_compile_definitions(test_unit_layer_vti PRIVATE SPREADMAP_TEST_WITH_VTK=1)
  endif()
endif()

# The effective and deposited thickness of the layers of a multi-layer bed (the characterise stage's).
if(TARGET spreadmap_workflow)
  spreadmap_test(unit layer_thickness SOURCES ${CMAKE_CURRENT_LIST_DIR}/layer_thickness_test.cpp LIBS spreadmap_workflow)
endif()
