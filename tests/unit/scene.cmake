# Scene building (host/scene): heap insertion, size distributions, coverage estimate, rough substrate.
if(TARGET spreadmap_scene)
  spreadmap_test(unit scene
    SOURCES ${CMAKE_CURRENT_LIST_DIR}/scene_heap_test.cpp ${CMAKE_CURRENT_LIST_DIR}/scene_distribution_test.cpp
            ${CMAKE_CURRENT_LIST_DIR}/scene_size_test.cpp
    LIBS spreadmap_scene)
  spreadmap_test(unit rough_substrate SOURCES ${CMAKE_CURRENT_LIST_DIR}/scene_rough_substrate_test.cpp
    LIBS spreadmap_scene spreadmap_engine)
endif()
