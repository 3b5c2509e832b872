# design: adaptive through the real binary on a small strip (seconds a case).
if(TARGET spreadmap AND TARGET spreadmap_analysis)
  spreadmap_test(integration adaptive SOURCES ${CMAKE_CURRENT_LIST_DIR}/adaptive_test.cpp
    LIBS spreadmap_analysis nlohmann_json::nlohmann_json TIMEOUT 900)
  add_dependencies(test_integration_adaptive spreadmap)
endif()
