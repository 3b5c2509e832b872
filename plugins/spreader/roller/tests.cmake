# spreader/roller: the cylinder's contacts against closed forms.
spreadmap_test(unit spreader_roller SOURCES ${CMAKE_CURRENT_LIST_DIR}/roller_test.cpp LIBS spreadmap_sdk)
