spreadmap_test(unit engine_fast_paths
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/engine_fast_paths_test.cpp ${CMAKE_CURRENT_LIST_DIR}/engine_pair_filter_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/engine_list_filter_test.cpp
  LIBS spreadmap_engine)
