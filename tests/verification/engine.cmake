spreadmap_test(verification engine_physics
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/engine_physics_test.cpp
  LIBS spreadmap_engine)
spreadmap_test(verification engine_gap_attraction
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/engine_gap_attraction_test.cpp
  LIBS spreadmap_engine spreadmap_sdk)
