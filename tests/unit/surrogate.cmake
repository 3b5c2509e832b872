# The analysis library (host/analysis); the surrogate plugins' tests are in their folders.
if(NOT TARGET spreadmap_analysis)  # until host/CMakeLists.txt adds add_subdirectory(analysis)
  add_subdirectory(${PROJECT_SOURCE_DIR}/host/analysis ${PROJECT_BINARY_DIR}/host/analysis)
endif()
spreadmap_test(unit analysis SOURCES ${CMAKE_CURRENT_LIST_DIR}/analysis_table_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/analysis_map_test.cpp ${CMAKE_CURRENT_LIST_DIR}/replicate_summary_test.cpp LIBS spreadmap_analysis)
spreadmap_test(unit confident_optimum SOURCES ${CMAKE_CURRENT_LIST_DIR}/analysis_confident_optimum_test.cpp
  LIBS gp_core spreadmap_analysis spreadmap_sdk)
