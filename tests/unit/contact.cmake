# Contact laws: schema lint and closed forms of the shared parts (contact_parts.hpp) and of what each
# law reports for the time step. Header-only: the laws are included directly.
spreadmap_test(unit contact
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/contact_schema_test.cpp ${CMAKE_CURRENT_LIST_DIR}/contact_parts_test.cpp
          ${CMAKE_CURRENT_LIST_DIR}/contact_loop_forms_test.cpp
  LIBS spreadmap_sdk)
