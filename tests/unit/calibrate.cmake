# host/workflow/calibrate: the angle fits on surfaces of known slope; the inverse step.
spreadmap_test(unit calibrate_angle_fit SOURCES ${CMAKE_CURRENT_LIST_DIR}/calibrate_angle_fit_test.cpp LIBS spreadmap_workflow)
# The inverse step: the closed-form identified set of a linear model, and the gp plugin on 16 runs.
spreadmap_test(unit calibrate_identify SOURCES ${CMAKE_CURRENT_LIST_DIR}/calibrate_identify_test.cpp
               LIBS spreadmap_workflow)
add_dependencies(test_unit_calibrate_identify plugin_surrogate_gp)
