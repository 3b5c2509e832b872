# The quickstart workflow itself, run once (resumable) and its outputs checked: every stage's files,
# the figures, the study's first-order trend, and report.html in a headless browser. Release tree only (minutes under a sanitizer).
if(TARGET spreadmap AND TARGET spreadmap_analysis)
  spreadmap_test(integration quickstart SOURCES ${CMAKE_CURRENT_LIST_DIR}/quickstart_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/report_test.cpp
    LIBS spreadmap_analysis nlohmann_json::nlohmann_json TIMEOUT 1200)
  add_dependencies(test_integration_quickstart spreadmap)
  if(TARGET spreadmap_render)
    target_compile_definitions(test_integration_quickstart PRIVATE SPREADMAP_TEST_FIGURES=1)
  endif()
endif()
