# The calibration round trip on the full example drum through the real binary (release only: the
# sanitizer builds run tests/workflow/calibrate_test.cpp's small drum).
if(TARGET spreadmap)
  spreadmap_test(integration calibrate_round_trip
    SOURCES ${CMAKE_CURRENT_LIST_DIR}/calibrate_round_trip_test.cpp
    LIBS spreadmap_test_process nlohmann_json::nlohmann_json TIMEOUT 600)
  add_dependencies(test_integration_calibrate_round_trip spreadmap plugin_contact_hooke_slider plugin_surrogate_gp)
endif()
