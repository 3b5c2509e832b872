# surrogate/bpnn: the network's training and prediction against closed forms and the study's function.
spreadmap_test(unit surrogate_bpnn SOURCES ${CMAKE_CURRENT_LIST_DIR}/bpnn_test.cpp LIBS bpnn_core spreadmap_sdk)
