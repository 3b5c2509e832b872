# Spreader geometry plugins (roller, blade): closed-form contacts, schema lint, module loading.
spreadmap_test(unit spreader
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/spreader_roller_test.cpp ${CMAKE_CURRENT_LIST_DIR}/spreader_blade_test.cpp
          ${CMAKE_CURRENT_LIST_DIR}/spreader_schema_test.cpp
  LIBS spreadmap_sdk ${CMAKE_DL_LIBS})
if(TARGET plugin_spreader_roller AND TARGET plugin_spreader_blade)
  add_dependencies(test_unit_spreader plugin_spreader_roller plugin_spreader_blade)
endif()
