# install() of the header-only table as the CMake package `bandlimit`: consumers write
#   find_package(bandlimit REQUIRED)
#   target_link_libraries(app PRIVATE bandlimit::generated)
# Headers go to <prefix>/include/bandlimit/, the GLSL include and the manifest to
# <prefix>/share/bandlimit/, the package files to <prefix>/share/cmake/bandlimit/ (arch-independent:
# nothing is compiled). Everything is in the install component `generated`, so
# `cmake --install build --component generated` installs exactly the table (docs/linking.md).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set_target_properties(bl_generated PROPERTIES EXPORT_NAME generated)
target_include_directories(bl_generated INTERFACE $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)

set(BL_INSTALL_CMAKEDIR ${CMAKE_INSTALL_DATADIR}/cmake/bandlimit)
set(BL_INSTALL_SHAREDIR ${CMAKE_INSTALL_DATADIR}/bandlimit)

install(TARGETS bl_generated EXPORT bandlimitTargets COMPONENT generated)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/generated/bandlimit/
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/bandlimit COMPONENT generated
  FILES_MATCHING PATTERN "*.hpp")
install(FILES ${PROJECT_SOURCE_DIR}/generated/bandlimit.glsl ${PROJECT_SOURCE_DIR}/generated/manifest.json
  DESTINATION ${BL_INSTALL_SHAREDIR} COMPONENT generated)
install(EXPORT bandlimitTargets NAMESPACE bandlimit:: DESTINATION ${BL_INSTALL_CMAKEDIR}
  COMPONENT generated)

configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/bandlimitConfig.cmake.in
  ${PROJECT_BINARY_DIR}/bandlimitConfig.cmake
  INSTALL_DESTINATION ${BL_INSTALL_CMAKEDIR}
  PATH_VARS BL_INSTALL_SHAREDIR)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/bandlimitConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion ARCH_INDEPENDENT)
install(FILES ${PROJECT_BINARY_DIR}/bandlimitConfig.cmake ${PROJECT_BINARY_DIR}/bandlimitConfigVersion.cmake
  DESTINATION ${BL_INSTALL_CMAKEDIR} COMPONENT generated)
