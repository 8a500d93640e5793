# `cmake --install build/release --prefix P`: the lgi executable, the headers,
# the libraries and a CMake package, so that another project writes
#   find_package(lgi CONFIG REQUIRED)
#   target_link_libraries(app PRIVATE lgi::experiments)   # or lgi::integrators, lgi::lie
# (README "Using lgi from another project"; tests/install/ builds such a project
# against an install made in the same test run).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

install(TARGETS lgi RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS lgi_lie lgi_integrators lgi_experiments lgi_warnings lgi_fp_policy
        EXPORT lgiTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
foreach(dir lie integrators experiments)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${dir} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
          FILES_MATCHING PATTERN "*.hpp")
endforeach()
install(FILES ${CMAKE_BINARY_DIR}/generated/lgi/build_info.hpp DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/lgi)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/experiments/scenes DESTINATION ${CMAKE_INSTALL_DATADIR}/lgi
        FILES_MATCHING PATTERN "*.toml")
# The sweep specs beside the scenes: their `scene = "../scenes/..."` resolves there too.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/experiments/sweeps DESTINATION ${CMAKE_INSTALL_DATADIR}/lgi
        FILES_MATCHING PATTERN "*.toml")
install(EXPORT lgiTargets NAMESPACE lgi:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/lgi)
set(LGI_INSTALL_SCENES_DIR ${CMAKE_INSTALL_DATADIR}/lgi/scenes)
set(LGI_INSTALL_SWEEPS_DIR ${CMAKE_INSTALL_DATADIR}/lgi/sweeps)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/lgiConfig.cmake.in
  ${CMAKE_BINARY_DIR}/lgiConfig.cmake INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/lgi
  PATH_VARS LGI_INSTALL_SCENES_DIR LGI_INSTALL_SWEEPS_DIR)
write_basic_package_version_file(${CMAKE_BINARY_DIR}/lgiConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/lgiConfig.cmake ${CMAKE_BINARY_DIR}/lgiConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/lgi)
