# host/core: units, schema validation, suggestions, atomic files, diagnostics and the plugin registry.
# The registry is tested against small faulty plugins built here, one folder each under
# <build>/tests/fixtures/<fault>/contact/, so that a test (or SPREADMAP_PLUGIN_PATH) can point at one.
set(SPREADMAP_FIXTURE_DIR ${CMAKE_CURRENT_BINARY_DIR}/fixtures)
set(SPREADMAP_FIXTURE_SOURCE ${CMAKE_CURRENT_LIST_DIR}/core_plugin_fixture.cpp)

# spreadmap_fixture_plugin(<fault> <file stem> [REGISTERS <name>] [DEFINES ...]) -> target fixture_<fault>
function(spreadmap_fixture_plugin fault stem)
  cmake_parse_arguments(F "" "REGISTERS" "DEFINES" ${ARGN})
  if(NOT F_REGISTERS)
    set(F_REGISTERS ${stem})
  endif()
  set(t fixture_${fault})
  add_library(${t} MODULE ${SPREADMAP_FIXTURE_SOURCE})
  target_link_libraries(${t} PRIVATE spreadmap_sdk)
  target_compile_definitions(${t} PRIVATE FIXTURE_NAME="${F_REGISTERS}" ${F_DEFINES})
  set_target_properties(${t} PROPERTIES PREFIX "" OUTPUT_NAME ${stem} CXX_VISIBILITY_PRESET hidden
    LIBRARY_OUTPUT_DIRECTORY ${SPREADMAP_FIXTURE_DIR}/${fault}/contact)
  set_property(GLOBAL APPEND PROPERTY SPREADMAP_FIXTURE_TARGETS ${t})
endfunction()

spreadmap_fixture_plugin(good fixture_law)
spreadmap_fixture_plugin(shadow fixture_law DEFINES FIXTURE_VERSION="2.0.0")
spreadmap_fixture_plugin(abi_mismatch abi_mismatch DEFINES FIXTURE_ABI=99u)
spreadmap_fixture_plugin(newer_minor newer_minor DEFINES FIXTURE_ABI=0xA0063u)  # ABI 10.99
spreadmap_fixture_plugin(stale_hooke_slider hooke_slider DEFINES FIXTURE_ABI=99u)  # shadows the real one
spreadmap_fixture_plugin(no_entry no_entry DEFINES FIXTURE_NO_ENTRY)
spreadmap_fixture_plugin(entry_variable entry_variable DEFINES FIXTURE_ENTRY_VARIABLE)
spreadmap_fixture_plugin(null_descriptor null_descriptor DEFINES FIXTURE_NULL_DESCRIPTOR)
spreadmap_fixture_plugin(kind_mismatch kind_mismatch DEFINES FIXTURE_KIND="spreader")
spreadmap_fixture_plugin(name_mismatch name_mismatch REGISTERS other_name)
spreadmap_fixture_plugin(refusing refusing DEFINES FIXTURE_FACTORY=1)
spreadmap_fixture_plugin(throwing throwing DEFINES FIXTURE_FACTORY=2)
# spreadmap_older_abi_plugin(<target> KIND <kind> NAME <stem> MINOR <n> SOURCES ... [LIBS ...]): a real
# plugin's sources built for an older minor ABI of this major, in <fixtures>/abi_10_<n>/<kind>/.
function(spreadmap_older_abi_plugin t)
  cmake_parse_arguments(F "" "KIND;NAME;MINOR" "SOURCES;LIBS" ${ARGN})
  add_library(${t} MODULE ${F_SOURCES})
  target_link_libraries(${t} PRIVATE spreadmap_sdk ${F_LIBS})
  target_compile_definitions(${t} PRIVATE SPREADMAP_TARGET_ABI_MINOR=${F_MINOR})
  set_target_properties(${t} PROPERTIES PREFIX "" OUTPUT_NAME ${F_NAME} CXX_VISIBILITY_PRESET hidden
    LIBRARY_OUTPUT_DIRECTORY ${SPREADMAP_FIXTURE_DIR}/abi_10_${F_MINOR}/${F_KIND})
endfunction()

# A real law built for ABI 10.0, whose ops table ends before 10.1's history_of: this host loads it.
spreadmap_older_abi_plugin(fixture_abi_10_0 KIND contact NAME hooke_history MINOR 0
  SOURCES ${PROJECT_SOURCE_DIR}/plugins/contact/hooke_history/hooke_history.cpp)
set_property(GLOBAL APPEND PROPERTY SPREADMAP_FIXTURE_TARGETS fixture_abi_10_0)
# A law without history built for ABI 10.2, before the engine handed laws queues of contacts (10.3):
# this host calls its whole-list loops.
spreadmap_older_abi_plugin(fixture_abi_10_2 KIND contact NAME hooke_slider MINOR 2
  SOURCES ${PROJECT_SOURCE_DIR}/plugins/contact/hooke_slider/hooke_slider.cpp)
set_property(GLOBAL APPEND PROPERTY SPREADMAP_FIXTURE_TARGETS fixture_abi_10_2)
get_property(SPREADMAP_FIXTURE_TARGETS GLOBAL PROPERTY SPREADMAP_FIXTURE_TARGETS)

spreadmap_test(unit core
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/core_units_test.cpp ${CMAKE_CURRENT_LIST_DIR}/core_schema_test.cpp
          ${CMAKE_CURRENT_LIST_DIR}/core_suggest_test.cpp ${CMAKE_CURRENT_LIST_DIR}/core_files_test.cpp
          ${CMAKE_CURRENT_LIST_DIR}/core_diagnostics_test.cpp ${CMAKE_CURRENT_LIST_DIR}/core_registry_test.cpp
          ${CMAKE_CURRENT_LIST_DIR}/core_csv_line_test.cpp
  LIBS spreadmap_core)
add_dependencies(test_unit_core ${SPREADMAP_FIXTURE_TARGETS})
target_compile_definitions(test_unit_core PRIVATE SPREADMAP_FIXTURE_DIR="${SPREADMAP_FIXTURE_DIR}")
