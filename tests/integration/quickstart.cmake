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

# SIGKILL at every rename: a preloaded shim kills the program just before its N-th rename(); each
# killed run resumes to the undisturbed run's bytes (release tree only: a sanitizer's runtime must come
# first, before any preload).
if(TARGET spreadmap)
  add_library(kill_at_rename MODULE ${CMAKE_CURRENT_LIST_DIR}/kill_at_rename.cpp)
  target_link_libraries(kill_at_rename PRIVATE ${CMAKE_DL_LIBS})
  spreadmap_test(integration kill SOURCES ${CMAKE_CURRENT_LIST_DIR}/kill_test.cpp
    LIBS spreadmap_analysis nlohmann_json::nlohmann_json TIMEOUT 1200)
  add_dependencies(test_integration_kill spreadmap kill_at_rename)
  target_compile_definitions(test_integration_kill PRIVATE SPREADMAP_KILL_SHIM="$<TARGET_FILE:kill_at_rename>")
endif()
