# The CUDA backend switch. SPREADMAP_ENABLE_CUDA = AUTO (default) | ON | OFF:
#   AUTO: on when CMake finds nvcc (on PATH, or at $CUDA_PATH / /usr/local/cuda) and this machine has
#         a GPU (nvidia-smi lists one): the kernels are most of a first build's time and run nowhere else;
#   ON:   nvcc is required, GPU or not (the test command asks for it: CI compiles the kernels);
#   OFF:  a CPU-only build.
# It sets SPREADMAP_WITH_CUDA (the resolved answer) and, when on, defines spreadmap_plugin_cuda(), the
# hook spreadmap_add_plugin() calls so that every contact and spreader plugin also carries its GPU
# kernels. No GPU is needed at build time: the architectures are explicit (SPREADMAP_CUDA_ARCHITECTURES).
set(SPREADMAP_ENABLE_CUDA AUTO CACHE STRING "Build the CUDA backend: AUTO (when nvcc is found), ON or OFF")
set_property(CACHE SPREADMAP_ENABLE_CUDA PROPERTY STRINGS AUTO ON OFF)
# 80: A100 SASS, which also runs on every 8.x GPU (RTX 30/40, L4, L40); 90: H100/H200 SASS plus PTX
# that the driver compiles for newer GPUs. Two targets keep nvcc's share of a 2-core CI build small.
set(SPREADMAP_CUDA_ARCHITECTURES "80-real;90" CACHE STRING "CUDA architectures of the GPU kernels (CMake syntax)")
# OFF: nvcc does not fuse a*b+c, so the GPU rounds every + - * / sqrt exactly as the CPU build does
# (ISO C++ mode never contracts) and both backends give the same numbers. ON is a little faster.
option(SPREADMAP_CUDA_FMAD "Let nvcc fuse multiply-adds in the GPU kernels" OFF)
# Every target that compiles GPU code takes these (the plugins' kernels and the resident stepper's:
# one fused integration step is enough for the backends to part after a few thousand steps).
set(SPREADMAP_CUDA_FP_OPTIONS $<$<AND:$<COMPILE_LANGUAGE:CUDA>,$<NOT:$<BOOL:${SPREADMAP_CUDA_FMAD}>>>:--fmad=false>)

set(SPREADMAP_WITH_CUDA OFF)
if(NOT SPREADMAP_ENABLE_CUDA STREQUAL "OFF")
  if(NOT CMAKE_CUDA_COMPILER AND NOT DEFINED ENV{CUDACXX})
    find_program(SPREADMAP_NVCC nvcc HINTS ENV CUDA_PATH ENV CUDA_HOME /usr/local/cuda PATH_SUFFIXES bin)
    if(SPREADMAP_NVCC)
      set(CMAKE_CUDA_COMPILER ${SPREADMAP_NVCC} CACHE FILEPATH "CUDA compiler")
    endif()
  endif()
  include(CheckLanguage)
  check_language(CUDA)
  set(spreadmap_gpu_here ON)
  if(SPREADMAP_ENABLE_CUDA STREQUAL "AUTO")
    execute_process(COMMAND nvidia-smi -L OUTPUT_VARIABLE spreadmap_gpus ERROR_QUIET RESULT_VARIABLE spreadmap_smi)
    if(NOT spreadmap_smi EQUAL 0 OR NOT spreadmap_gpus MATCHES "GPU")
      set(spreadmap_gpu_here OFF)
    endif()
  endif()
  if(CMAKE_CUDA_COMPILER AND NOT spreadmap_gpu_here)
    message(STATUS "spreadmap: nvcc found but no GPU on this machine: the CUDA kernels are not built "
                   "(-DSPREADMAP_ENABLE_CUDA=ON builds them anyway)")
  elseif(CMAKE_CUDA_COMPILER)
    set(SPREADMAP_WITH_CUDA ON)
  elseif(SPREADMAP_ENABLE_CUDA STREQUAL "ON")
    message(FATAL_ERROR "SPREADMAP_ENABLE_CUDA=ON but no CUDA compiler was found: install the CUDA toolkit, "
                        "put nvcc on PATH or pass -DCMAKE_CUDA_COMPILER=/path/to/nvcc; or use AUTO or OFF")
  endif()
endif()

if(NOT SPREADMAP_WITH_CUDA)
  message(STATUS "spreadmap: CUDA backend OFF (SPREADMAP_ENABLE_CUDA=${SPREADMAP_ENABLE_CUDA}; nvcc not used)")
  return()
endif()

set(CMAKE_CUDA_ARCHITECTURES ${SPREADMAP_CUDA_ARCHITECTURES})
enable_language(CUDA)
# The SDK asks for C++20 (cxx_std_20), which CMake also applies to CUDA sources; CMake < 3.26 does not
# know nvcc's C++20 flag (nvcc >= 12 has it), so tell it.
if(NOT DEFINED CMAKE_CUDA20_STANDARD_COMPILE_OPTION AND CMAKE_CUDA_COMPILER_VERSION VERSION_GREATER_EQUAL 12.0)
  set(CMAKE_CUDA20_STANDARD_COMPILE_OPTION "-std=c++20")
  set(CMAKE_CUDA20_EXTENSION_COMPILE_OPTION "-std=c++20")
endif()
# nvcc preprocesses with the host compiler, so the C++ compiler's implicit include folders are nvcc's
# too; without this, imported targets' -isystem /usr/include breaks <cmath>'s #include_next.
list(APPEND CMAKE_CUDA_IMPLICIT_INCLUDE_DIRECTORIES ${CMAKE_CXX_IMPLICIT_INCLUDE_DIRECTORIES})
find_package(CUDAToolkit REQUIRED)
set(SPREADMAP_CUDA_INCLUDE_DIR ${PROJECT_SOURCE_DIR}/host/cuda/include)
set(SPREADMAP_CUDA_COMPANION_IN ${PROJECT_SOURCE_DIR}/host/cuda/companion.cu.in)
set(spreadmap_cuda_banner
    "spreadmap: CUDA backend ON: nvcc ${CMAKE_CUDA_COMPILER_VERSION} builds GPU kernels for architectures ${CMAKE_CUDA_ARCHITECTURES}")
message(STATUS "${spreadmap_cuda_banner}")
# The same line in every build log, before the first nvcc call (CI logs show the build, not the configure).
add_custom_target(spreadmap_cuda_architectures ALL COMMAND ${CMAKE_COMMAND} -E echo "${spreadmap_cuda_banner}" VERBATIM)

# spreadmap_plugin_cuda(<target> <kind> <sources>): called by spreadmap_add_plugin(). For a contact or
# spreader plugin it generates <name>_cuda.cu from companion.cu.in around the source that holds the
# registration macro, compiles it with nvcc into the same module (so the module exports the CUDA entry
# point beside spreadmap_plugin_v1) and marks the descriptor SM_BACKEND_CPU | SM_BACKEND_CUDA. The
# registration source is compiled twice, so it may hold only the macro and inline or template code
# (as every in-tree plugin does); anything else belongs in a header or another source file.
function(spreadmap_plugin_cuda target kind sources)
  if(NOT kind MATCHES "^(contact|spreader)$")
    return()
  endif()
  get_target_property(NAME ${target} OUTPUT_NAME)
  set(KIND ${kind})
  set(companion)
  foreach(src IN LISTS sources)
    get_filename_component(SOURCE ${src} ABSOLUTE)
    if(NOT SOURCE MATCHES "\\.(cpp|cc|cxx)$")
      continue()
    endif()
    file(STRINGS ${SOURCE} registration REGEX "SPREADMAP_(CONTACT|SPREADER)_PLUGIN[ \t]*\\(")
    if(registration)
      set(companion ${CMAKE_CURRENT_BINARY_DIR}/${NAME}_cuda.cu)
      configure_file(${SPREADMAP_CUDA_COMPANION_IN} ${companion} @ONLY)
      break()
    endif()
  endforeach()
  if(NOT companion)
    message(WARNING "${kind}/${NAME}: no source holds SPREADMAP_${kind}_PLUGIN(...); built for the CPU only")
    return()
  endif()
  target_sources(${target} PRIVATE ${companion})
  target_include_directories(${target} PRIVATE ${SPREADMAP_CUDA_INCLUDE_DIR})
  target_compile_definitions(${target} PRIVATE "SPREADMAP_BACKENDS=(SM_BACKEND_CPU|SM_BACKEND_CUDA)")
  target_compile_options(${target} PRIVATE ${SPREADMAP_CUDA_FP_OPTIONS})
  # A static CUDA runtime: the module loads on machines without the driver or the toolkit, and its
  # symbols stay inside (hidden), so the module still exports only its entry points. Linked as the
  # toolkit's imported target (full path): the C++ linker that links the module knows no CUDA folders.
  set_target_properties(${target} PROPERTIES CUDA_RUNTIME_LIBRARY None CUDA_VISIBILITY_PRESET hidden)
  target_link_libraries(${target} PRIVATE CUDA::cudart_static)
  target_link_options(${target} PRIVATE "LINKER:--exclude-libs,ALL")
  add_dependencies(${target} spreadmap_cuda_architectures)
endfunction()
