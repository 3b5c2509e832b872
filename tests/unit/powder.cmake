# The powder library (host/powder): heap insertion, size distributions, coverage estimate, rough substrate.
if(TARGET spreadmap_powder)
  spreadmap_test(unit powder_library
    SOURCES ${CMAKE_CURRENT_LIST_DIR}/powder_heap_test.cpp ${CMAKE_CURRENT_LIST_DIR}/powder_distribution_test.cpp
            ${CMAKE_CURRENT_LIST_DIR}/powder_size_test.cpp
    LIBS spreadmap_powder)
  spreadmap_test(unit rough_substrate SOURCES ${CMAKE_CURRENT_LIST_DIR}/powder_rough_substrate_test.cpp
    LIBS spreadmap_powder spreadmap_engine)
endif()
