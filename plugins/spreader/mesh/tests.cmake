# spreader/mesh: STL reading, the mesh's nearest-feature contacts against closed forms and analytic
# walls, and the spreader through its functor.
spreadmap_test(unit mesh_stl
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/mesh_stl_test.cpp
  LIBS spreadmap_sdk)
spreadmap_test(unit mesh_contact
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/mesh_contact_test.cpp
  LIBS spreadmap_engine)
spreadmap_test(unit mesh_spreader
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/mesh_spreader_test.cpp ${CMAKE_CURRENT_LIST_DIR}/mesh.cpp
  LIBS spreadmap_sdk)
