# Exported package: an outside project does find_package(pliant) and links pliant::estimation.
include(CMakePackageConfigHelpers)
set(PLIANT_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/pliant)
install(EXPORT pliantTargets NAMESPACE pliant:: DESTINATION ${PLIANT_CMAKE_DIR})
configure_package_config_file(cmake/pliantConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/pliantConfig.cmake INSTALL_DESTINATION ${PLIANT_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/pliantConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/pliantConfig.cmake
  ${CMAKE_CURRENT_BINARY_DIR}/pliantConfigVersion.cmake DESTINATION ${PLIANT_CMAKE_DIR})
