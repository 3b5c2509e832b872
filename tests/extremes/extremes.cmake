# The stability suite (issue 8): small scenes at the extremes of every parameter. `engine` drives the
# engine API with the real plugins' code (hooke_slider, roller) compiled in from their headers;
# `workflow` runs the spreadmap binary on small workflow files for the whole path (exit codes,
# messages, output files). Label: extremes (from the folder).
# Their scenes and checks, compiled once for both executables.
add_library(spreadmap_extremes_support STATIC ${CMAKE_CURRENT_LIST_DIR}/scene.cpp ${CMAKE_CURRENT_LIST_DIR}/checks.cpp)
target_include_directories(spreadmap_extremes_support PUBLIC ${PROJECT_SOURCE_DIR}/tests ${PROJECT_SOURCE_DIR})
target_link_libraries(spreadmap_extremes_support PUBLIC spreadmap_engine fmt::fmt)

spreadmap_test(extremes engine
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/spreader_extremes_test.cpp ${CMAKE_CURRENT_LIST_DIR}/material_extremes_test.cpp
          ${CMAKE_CURRENT_LIST_DIR}/time_step_extremes_test.cpp ${CMAKE_CURRENT_LIST_DIR}/degenerate_scenes_test.cpp
          ${CMAKE_CURRENT_LIST_DIR}/watch.cpp
  LIBS spreadmap_extremes_support)

# Runs the binary as a child process with the workflow suite's helper (tests/workflow/process.cpp).
spreadmap_test(extremes workflow
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/workflow_extremes_test.cpp
  LIBS spreadmap_extremes_support spreadmap_test_process)
foreach(needed spreadmap plugin_contact_hooke_slider plugin_spreader_roller)
  if(TARGET ${needed})
    add_dependencies(test_extremes_workflow ${needed})
  endif()
endforeach()
