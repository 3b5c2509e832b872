# surrogate/gp: the Gaussian process's fit, predictive spread and hyperparameters.
spreadmap_test(unit surrogate_gp SOURCES ${CMAKE_CURRENT_LIST_DIR}/gp_test.cpp LIBS gp_core spreadmap_sdk)
