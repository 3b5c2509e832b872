spreadmap_test(verification engine_physics
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/engine_physics_test.cpp
  LIBS spreadmap_engine)
