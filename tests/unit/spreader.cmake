# Spreader geometry plugins (roller, blade): schema lint and module loading (their contacts are tested
# in their folders, plugins/spreader/<name>/tests.cmake).
spreadmap_test(unit spreader
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/spreader_schema_test.cpp
  LIBS spreadmap_sdk ${CMAKE_DL_LIBS})
if(TARGET plugin_spreader_roller AND TARGET plugin_spreader_blade)
  add_dependencies(test_unit_spreader plugin_spreader_roller plugin_spreader_blade)
endif()
