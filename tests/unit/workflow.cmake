# host/workflow: the local executor's pool of case threads, with stand-ins for the cases.
spreadmap_test(unit workflow SOURCES ${CMAKE_CURRENT_LIST_DIR}/workflow_local_executor_test.cpp LIBS spreadmap_workflow)
