# The warnings every spreadmap target compiles with: CMakeLists.txt adds them to the whole tree, and
# spreadmap_add_plugin() to the plugins it builds outside the tree. nvcc passes them to the host
# compiler for the host half of CUDA sources. GCC 12 reports a bogus -Wrestrict inside libstdc++'s
# <string> for any "literal" + std::string temporary (GCC bugs 105329 and 105651, fixed in GCC 13), so
# that one warning is off for GCC 12 and older.
set(SPREADMAP_WARNING_OPTIONS
  $<$<COMPILE_LANG_AND_ID:CXX,GNU,Clang>:-Wall$<SEMICOLON>-Wextra>
  $<$<AND:$<COMPILE_LANG_AND_ID:CXX,GNU>,$<VERSION_LESS:$<CXX_COMPILER_VERSION>,13>>:-Wno-restrict>
  $<$<COMPILE_LANG_AND_ID:CUDA,NVIDIA>:-Xcompiler=-Wall$<COMMA>-Wextra>)
# Under AddressSanitizer GCC 12 also warns -Wmaybe-uninitialized inside libstdc++'s <regex> (the
# std::function members of its automaton's states) for every std::regex, so that warning is off in
# sanitizer builds (the asan preset); the release build keeps it.
if(CMAKE_CXX_FLAGS MATCHES "-fsanitize=[a-z,]*address")
  list(APPEND SPREADMAP_WARNING_OPTIONS $<$<COMPILE_LANG_AND_ID:CXX,GNU>:-Wno-maybe-uninitialized>)
endif()
