# spreader/oscillating_roller: its motion in closed form, and the module through the ABI.
spreadmap_test(unit oscillating_roller
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/oscillating_roller_test.cpp
  LIBS spreadmap_sdk ${CMAKE_DL_LIBS})
target_compile_definitions(test_unit_oscillating_roller PRIVATE
  OSCILLATING_ROLLER_MODULE="$<TARGET_FILE:plugin_spreader_oscillating_roller>")
add_dependencies(test_unit_oscillating_roller plugin_spreader_oscillating_roller)
