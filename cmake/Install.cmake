# Installs the library, its public headers and a CMake package: find_package(fuzzygait).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

get_property(fuzzygait_libraries GLOBAL PROPERTY FUZZYGAIT_LIBRARIES)
install(TARGETS fuzzygait ${fuzzygait_libraries}
        EXPORT fuzzygaitTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS fuzzygait_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY include/fuzzygait DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY controllers/ DESTINATION ${CMAKE_INSTALL_DATADIR}/fuzzygait/controllers)
install(EXPORT fuzzygaitTargets NAMESPACE fuzzygait::
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/fuzzygait)
configure_package_config_file(cmake/fuzzygaitConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/fuzzygaitConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/fuzzygait)
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/fuzzygaitConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/fuzzygaitConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/fuzzygaitConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/fuzzygait)
