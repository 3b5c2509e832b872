# metrics/layer against closed forms of ideal monolayers (square, rotated square, hexagonal, one sphere).
if(TARGET layer_core)
  spreadmap_test(verification layer SOURCES ${CMAKE_CURRENT_LIST_DIR}/layer_closed_form_test.cpp LIBS layer_core)
endif()
