# metrics/layer against closed forms of ideal monolayers (square, rotated square, hexagonal, one sphere)
# and of packing against depth in simple cubic and face-centred cubic lattices.
if(TARGET layer_core)
  spreadmap_test(verification layer
    SOURCES ${CMAKE_CURRENT_LIST_DIR}/layer_closed_form_test.cpp ${CMAKE_CURRENT_LIST_DIR}/layer_depth_profile_test.cpp
    LIBS layer_core)
endif()
