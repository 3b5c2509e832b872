# The surrogate plugins loaded from their .so files, scored on the study's 45-point design.
spreadmap_test(verification surrogate_study SOURCES ${CMAKE_CURRENT_LIST_DIR}/surrogate_study_test.cpp
  LIBS spreadmap_analysis ${CMAKE_DL_LIBS} TIMEOUT 120)
add_dependencies(test_verification_surrogate_study plugin_surrogate_bpnn plugin_surrogate_gp)
