# Contact laws against closed forms, driven through the SDK's pair/wall loops by a minimal velocity-Verlet
# integrator (contact_support.hpp): conformance of every law, hooke_slider's normal impacts, friction,
# head-on impacts without friction, the cohesion part, the rolling spring.
spreadmap_test(verification contact
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/contact_conformance_test.cpp ${CMAKE_CURRENT_LIST_DIR}/contact_hooke_slider_test.cpp
          ${CMAKE_CURRENT_LIST_DIR}/contact_friction_test.cpp ${CMAKE_CURRENT_LIST_DIR}/contact_head_on_test.cpp
          ${CMAKE_CURRENT_LIST_DIR}/contact_cohesion_test.cpp ${CMAKE_CURRENT_LIST_DIR}/contact_rolling_spring_test.cpp
  LIBS spreadmap_sdk)
