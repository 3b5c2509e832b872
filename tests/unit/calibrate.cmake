# host/workflow/calibrate: the angle fits on surfaces of known slope.
spreadmap_test(unit calibrate_angle_fit SOURCES ${CMAKE_CURRENT_LIST_DIR}/calibrate_angle_fit_test.cpp LIBS spreadmap_workflow)
