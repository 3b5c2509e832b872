# Figures (host/render): headless tests, they start their own Xvfb when DISPLAY is unset.
if(TARGET spreadmap_render)
  find_package(MPI COMPONENTS C QUIET)
  find_package(VTK 9.1 REQUIRED COMPONENTS IOImage CommonCore)
  spreadmap_test(unit render_figures
    SOURCES ${CMAKE_CURRENT_LIST_DIR}/render_figures_test.cpp ${CMAKE_CURRENT_LIST_DIR}/render_image_check.cpp
    LIBS spreadmap_render VTK::IOImage VTK::CommonCore)
  # axis ticks and contour levels on NaN, infinite and huge ranges (canvas2d.hpp, private to render)
  spreadmap_test(unit render_ticks
    SOURCES ${CMAKE_CURRENT_LIST_DIR}/render_ticks_test.cpp
    LIBS spreadmap_render VTK::CommonCore)
  spreadmap_test(unit render_display
    SOURCES ${CMAKE_CURRENT_LIST_DIR}/render_display_test.cpp
    LIBS spreadmap_render)
endif()
