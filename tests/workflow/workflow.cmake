# The program as users run it: the real binary in child processes (tests/workflow/process.hpp).
# Catalogue of malformed inputs (data/bad/), the command line, kill-and-resume, and an out-of-tree
# plugin built against the installed SDK. They need the binary, every plugin and the fixture plugins
# of tests/unit/core.cmake.
set(workflow_needs spreadmap ${SPREADMAP_FIXTURE_TARGETS})
file(GLOB plugin_cmakelists ${PROJECT_SOURCE_DIR}/plugins/*/*/CMakeLists.txt)
foreach(f IN LISTS plugin_cmakelists)
  get_filename_component(dir ${f} DIRECTORY)
  get_filename_component(name ${dir} NAME)
  get_filename_component(kind_dir ${dir} DIRECTORY)
  get_filename_component(kind ${kind_dir} NAME)
  if(TARGET plugin_${kind}_${name})
    list(APPEND workflow_needs plugin_${kind}_${name})
  endif()
endforeach()

function(spreadmap_workflow_test name)
  cmake_parse_arguments(W "" "TIMEOUT" "SOURCES" ${ARGN})
  spreadmap_test(workflow ${name} SOURCES ${W_SOURCES} LIBS spreadmap_test_process spreadmap_sdk TIMEOUT ${W_TIMEOUT})
  add_dependencies(test_workflow_${name} ${workflow_needs})
  target_compile_definitions(test_workflow_${name} PRIVATE SPREADMAP_FIXTURE_DIR="${SPREADMAP_FIXTURE_DIR}")
endfunction()

spreadmap_workflow_test(catalogue SOURCES ${CMAKE_CURRENT_LIST_DIR}/catalogue_test.cpp TIMEOUT 120)
spreadmap_workflow_test(cli SOURCES ${CMAKE_CURRENT_LIST_DIR}/cli_test.cpp TIMEOUT 120)
# The command and stage tables against what the program prints.
spreadmap_workflow_test(command_table SOURCES ${CMAKE_CURRENT_LIST_DIR}/command_table_test.cpp TIMEOUT 120)
target_link_libraries(test_workflow_command_table PRIVATE spreadmap_cli)
spreadmap_workflow_test(resume SOURCES ${CMAKE_CURRENT_LIST_DIR}/resume_test.cpp TIMEOUT 600)
# What a run reads back is checked: damaged checkpoints and heaps, replaced states, stale temporaries.
spreadmap_workflow_test(read_back SOURCES ${CMAKE_CURRENT_LIST_DIR}/read_back_test.cpp TIMEOUT 600)
target_link_libraries(test_workflow_read_back PRIVATE spreadmap_core)  # stable_hash
spreadmap_workflow_test(plugin_sdk SOURCES ${CMAKE_CURRENT_LIST_DIR}/plugin_sdk_test.cpp TIMEOUT 300)
# The engine as a library: examples/engine_two_spheres built against the installed package and run.
spreadmap_workflow_test(engine_library SOURCES ${CMAKE_CURRENT_LIST_DIR}/engine_library_test.cpp TIMEOUT 300)
# The tests that install the package and build against it (installed_package.hpp).
foreach(t plugin_sdk engine_library)
  target_compile_definitions(test_workflow_${t} PRIVATE
    SPREADMAP_CMAKE_COMMAND="${CMAKE_COMMAND}" SPREADMAP_CXX_COMPILER="${CMAKE_CXX_COMPILER}")
endforeach()
# A program linking the installed static engine needs the flags it was compiled with (a sanitizer's
# runtime in the asan preset; nothing in release).
target_compile_definitions(test_workflow_engine_library PRIVATE
  SPREADMAP_BUILD_CXX_FLAGS="${CMAKE_CXX_FLAGS}" SPREADMAP_BUILD_EXE_LINKER_FLAGS="${CMAKE_EXE_LINKER_FLAGS}")
spreadmap_workflow_test(stage_commands SOURCES ${CMAKE_CURRENT_LIST_DIR}/stage_commands_test.cpp TIMEOUT 300)
target_link_libraries(test_workflow_stage_commands PRIVATE Eigen3::Eigen)
if(TARGET spreadmap_render)
  target_compile_definitions(test_workflow_stage_commands PRIVATE SPREADMAP_TEST_FIGURES=1)
endif()
spreadmap_workflow_test(mutation SOURCES ${CMAKE_CURRENT_LIST_DIR}/mutation_test.cpp TIMEOUT 900)
target_link_libraries(test_workflow_mutation PRIVATE yaml-cpp)
# The example scenes (examples/scenes/) run by `spreadmap simulate` against their closed forms.
spreadmap_workflow_test(scenes SOURCES ${CMAKE_CURRENT_LIST_DIR}/scenes_test.cpp TIMEOUT 300)
target_link_libraries(test_workflow_scenes PRIVATE spreadmap_workflow)  # calibrate's heap_angle
# `spreadmap calibrate` on a small drum: kept runs, a changed scene, refusals (the round trip: integration/).
spreadmap_workflow_test(calibrate SOURCES ${CMAKE_CURRENT_LIST_DIR}/calibrate_test.cpp TIMEOUT 300)
# Replicates: different heaps per point, their mean and std in metrics.csv, the GP given their scatter.
spreadmap_workflow_test(replicates SOURCES ${CMAKE_CURRENT_LIST_DIR}/replicates_test.cpp TIMEOUT 300)
# The verify stage on a tiny version of workflows/quickstart_verify.yaml.
spreadmap_workflow_test(verify SOURCES ${CMAKE_CURRENT_LIST_DIR}/verify_test.cpp TIMEOUT 300)
if(TARGET spreadmap_render)
  target_compile_definitions(test_workflow_verify PRIVATE SPREADMAP_TEST_FIGURES=1)
endif()
# A heap spread onto a rough substrate (scene.substrate.roughness), through the binary.
spreadmap_workflow_test(rough_substrate SOURCES ${CMAKE_CURRENT_LIST_DIR}/rough_substrate_test.cpp TIMEOUT 300)
target_link_libraries(test_workflow_rough_substrate PRIVATE spreadmap_workflow)
# The user guide (README.md, docs/*.md) kept true: its complete YAML files validate, its command lines
# name real commands and options, its links reach their pages and headings.
spreadmap_workflow_test(guide_examples SOURCES ${CMAKE_CURRENT_LIST_DIR}/guide_examples_test.cpp TIMEOUT 300)
# Issue 37, nothing lost, nothing stale, nothing crashes: the run directory lock, models predicting
# NaN, messages of bad options, a full disk.
spreadmap_workflow_test(integrity SOURCES ${CMAKE_CURRENT_LIST_DIR}/integrity_test.cpp TIMEOUT 300)
# A machine's layers (scene.machine): the feed, the dropping platform, the overflow, per-layer resume.
spreadmap_workflow_test(machine SOURCES ${CMAKE_CURRENT_LIST_DIR}/machine_test.cpp TIMEOUT 600)
target_link_libraries(test_workflow_machine PRIVATE spreadmap_workflow)  # engine::read_vtp
