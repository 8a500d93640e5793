# Build provenance written into every output file (experiments/OUTPUT.md, /parameters):
# git describe, compiler, flags and build type.
find_package(Git QUIET)
set(LGI_GIT_DESCRIBE "unknown")
if(GIT_FOUND)
  execute_process(COMMAND ${GIT_EXECUTABLE} describe --always --dirty
    WORKING_DIRECTORY ${CMAKE_SOURCE_DIR}
    OUTPUT_VARIABLE _describe OUTPUT_STRIP_TRAILING_WHITESPACE
    RESULT_VARIABLE _rc ERROR_QUIET)
  if(_rc EQUAL 0 AND _describe)
    set(LGI_GIT_DESCRIBE "${_describe}")
  endif()
endif()
string(TOUPPER "${CMAKE_BUILD_TYPE}" _bt)
# The floating-point policy's flags as cmake/warnings.cmake sets them (LGI_FP_CONTRACT:
# off by default, fast in the release-native preset, whose -march=native is in CMAKE_CXX_FLAGS).
set(LGI_CXX_FLAGS "${CMAKE_CXX_FLAGS} ${CMAKE_CXX_FLAGS_${_bt}} -std=c++20 -ffp-contract=${LGI_FP_CONTRACT} -fno-fast-math")
string(STRIP "${LGI_CXX_FLAGS}" LGI_CXX_FLAGS)
set(LGI_COMPILER "${CMAKE_CXX_COMPILER_ID} ${CMAKE_CXX_COMPILER_VERSION}")
configure_file(${CMAKE_SOURCE_DIR}/cmake/build_info.hpp.in
  ${CMAKE_BINARY_DIR}/generated/lgi/build_info.hpp @ONLY)
