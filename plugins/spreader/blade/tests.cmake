# spreader/blade: the slab's and its rounded edges' contacts against closed forms.
spreadmap_test(unit spreader_blade SOURCES ${CMAKE_CURRENT_LIST_DIR}/blade_test.cpp LIBS spreadmap_sdk)
