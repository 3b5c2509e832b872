# The stability suite (issue 8): small scenes at the extremes of every parameter. `engine` drives the
# engine API with the real plugins' code (hooke_slider, roller) compiled in from their headers;
# `workflow` runs the spreadmap binary on small workflow files for the whole path (exit codes,
# messages, output files). Label: extremes (from the folder).
set(extremes_support ${CMAKE_CURRENT_LIST_DIR}/scene.cpp ${CMAKE_CURRENT_LIST_DIR}/checks.cpp)

spreadmap_test(extremes engine
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/spreader_extremes_test.cpp ${CMAKE_CURRENT_LIST_DIR}/material_extremes_test.cpp
          ${CMAKE_CURRENT_LIST_DIR}/time_step_extremes_test.cpp ${CMAKE_CURRENT_LIST_DIR}/degenerate_scenes_test.cpp
          ${CMAKE_CURRENT_LIST_DIR}/watch.cpp ${extremes_support}
  LIBS spreadmap_engine)

# Runs the binary as a child process with the workflow suite's helper (tests/workflow/process.cpp).
spreadmap_test(extremes workflow
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/workflow_extremes_test.cpp ${PROJECT_SOURCE_DIR}/tests/workflow/process.cpp
          ${extremes_support}
  LIBS spreadmap_engine)
foreach(needed spreadmap plugin_contact_hooke_slider plugin_spreader_roller)
  if(TARGET ${needed})
    add_dependencies(test_extremes_workflow ${needed})
  endif()
endforeach()
