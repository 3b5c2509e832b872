# Beyond one machine (host/cluster/): the simulate stage's cases on MPI ranks and as Slurm job
# arrays, run on a reduced copy of the quickstart (data/mini_quickstart.yaml: 300 spheres, 6 mm of
# travel, 2 x 2 cases; seconds per run). Like the workflow tests they run the real binary.
set(cluster_needs spreadmap plugin_contact_hooke_slider plugin_spreader_roller plugin_metrics_layer)
set(cluster_ready TRUE)
foreach(t IN LISTS cluster_needs)
  if(NOT TARGET ${t})
    set(cluster_ready FALSE)
  endif()
endforeach()

if(cluster_ready AND TARGET spreadmap_cluster)
  get_property(cluster_mpi GLOBAL PROPERTY SPREADMAP_WITH_MPI)
  find_program(SPREADMAP_MPIEXEC NAMES mpirun mpiexec)
  function(spreadmap_cluster_test name)
    cmake_parse_arguments(C "" "TIMEOUT" "SOURCES" ${ARGN})
    spreadmap_test(cluster ${name} SOURCES ${C_SOURCES}
      LIBS spreadmap_test_process nlohmann_json::nlohmann_json TIMEOUT ${C_TIMEOUT})
    add_dependencies(test_cluster_${name} ${cluster_needs})
    target_compile_definitions(test_cluster_${name} PRIVATE SPREADMAP_MPIEXEC="${SPREADMAP_MPIEXEC}")
  endfunction()

  spreadmap_cluster_test(options SOURCES ${CMAKE_CURRENT_LIST_DIR}/options_test.cpp TIMEOUT 120)
  spreadmap_cluster_test(slurm SOURCES ${CMAKE_CURRENT_LIST_DIR}/slurm_test.cpp TIMEOUT 300)
  target_link_libraries(test_cluster_slurm PRIVATE spreadmap_cluster)
  if(cluster_mpi AND SPREADMAP_MPIEXEC)
    spreadmap_cluster_test(mpi SOURCES ${CMAKE_CURRENT_LIST_DIR}/mpi_test.cpp TIMEOUT 900)
    spreadmap_cluster_test(mpi_kill SOURCES ${CMAKE_CURRENT_LIST_DIR}/mpi_kill_test.cpp TIMEOUT 300)
  else()
    message(STATUS "tests/cluster: no MPI in this build (or no mpirun): the --executor mpi tests are left out")
  endif()

  # A real one-node Slurm on localhost (munge, slurmctld, slurmd started by the script itself). It
  # runs where Debian's slurm-wlm and munge are installed; elsewhere it is `manual` (see the script).
  find_program(SPREADMAP_SLURMCTLD slurmctld PATHS /usr/sbin)
  find_program(SPREADMAP_SLURMD slurmd PATHS /usr/sbin)
  find_program(SPREADMAP_MUNGED munged PATHS /usr/sbin)
  find_program(SPREADMAP_SBATCH sbatch)
  set(slurm_labels cluster)
  if(NOT (SPREADMAP_SLURMCTLD AND SPREADMAP_SLURMD AND SPREADMAP_MUNGED AND SPREADMAP_SBATCH))
    list(APPEND slurm_labels manual)
    message(STATUS "tests/cluster: slurm-wlm or munge not installed: cluster.SlurmLocalhost is manual")
  endif()
  add_test(NAME cluster.SlurmLocalhost.ArrayJobsRunTheQuickstartToCompletion
    COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/slurm_localhost.sh ${PROJECT_BINARY_DIR}/bin/spreadmap)
  set_tests_properties(cluster.SlurmLocalhost.ArrayJobsRunTheQuickstartToCompletion PROPERTIES
    LABELS "${slurm_labels}" TIMEOUT 600 RUN_SERIAL TRUE ENVIRONMENT "OMP_NUM_THREADS=1;SPREADMAP_PLUGIN_PATH=")
endif()
