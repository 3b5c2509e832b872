spreadmap_test(unit engine_core
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/engine_core_test.cpp
  LIBS spreadmap_engine)
spreadmap_test(unit engine_io
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/engine_io_test.cpp
  LIBS spreadmap_engine)
