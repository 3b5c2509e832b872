spreadmap_test(unit engine_core
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/engine_core_test.cpp
  LIBS spreadmap_engine)
spreadmap_test(unit engine_io
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/engine_io_test.cpp
  LIBS spreadmap_engine)
spreadmap_test(unit engine_kick_drift
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/engine_kick_drift_test.cpp
  LIBS spreadmap_engine)
spreadmap_test(unit engine_thread_team
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/engine_thread_team_test.cpp ${CMAKE_CURRENT_LIST_DIR}/engine_cell_sort_test.cpp
  LIBS spreadmap_engine)
spreadmap_test(unit engine_plugin_law
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/engine_plugin_law_test.cpp
  LIBS spreadmap_engine)
add_dependencies(test_unit_engine_plugin_law plugin_contact_hooke_slider plugin_contact_hooke_history
  plugin_contact_hertz_mindlin fixture_abi_10_0 fixture_abi_10_2)
target_compile_definitions(test_unit_engine_plugin_law PRIVATE SPREADMAP_FIXTURE_DIR="${SPREADMAP_FIXTURE_DIR}")
spreadmap_test(unit engine_team_tuner
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/engine_team_tuner_test.cpp
  LIBS spreadmap_engine)
