# Install rules and the relocatable package config for find_package(OpenCVShading CONFIG).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(OPENCV_SHADING_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/OpenCVShading)

install(TARGETS opencv_shading EXPORT OpenCVShadingTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY modules/shading/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT OpenCVShadingTargets NAMESPACE OpenCVShading:: DESTINATION ${OPENCV_SHADING_CMAKE_DIR})

configure_package_config_file(cmake/OpenCVShadingConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/OpenCVShadingConfig.cmake
  INSTALL_DESTINATION ${OPENCV_SHADING_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/OpenCVShadingConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/OpenCVShadingConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/OpenCVShadingConfigVersion.cmake
        DESTINATION ${OPENCV_SHADING_CMAKE_DIR})
