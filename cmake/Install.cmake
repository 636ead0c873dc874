# Installs the two libraries as components of one CMake package, the program and the shipped
# controller sets:
#   find_package(fuzzygait COMPONENTS runtime)           fuzzygait::runtime, no dependencies
#   find_package(fuzzygait COMPONENTS runtime offline)   also fuzzygait::offline
#   cmake --install build --component runtime            the runtime alone
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)
set(package_dir ${CMAKE_INSTALL_LIBDIR}/cmake/fuzzygait)

install(TARGETS fuzzygait_runtime EXPORT fuzzygaitRuntimeTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT runtime
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
foreach(part IN ITEMS fuzzy rig terrain gait path body)
  install(DIRECTORY include/fuzzygait/${part} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/fuzzygait
          COMPONENT runtime)
endforeach()
install(FILES include/fuzzygait/compiler.hpp include/fuzzygait/fuzzygait.h
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/fuzzygait COMPONENT runtime)
install(EXPORT fuzzygaitRuntimeTargets NAMESPACE fuzzygait:: DESTINATION ${package_dir}
        COMPONENT runtime)

install(TARGETS fuzzygait_offline EXPORT fuzzygaitOfflineTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT offline
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
foreach(part IN ITEMS eval learn io)
  install(DIRECTORY include/fuzzygait/${part} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/fuzzygait
          COMPONENT offline)
endforeach()
install(EXPORT fuzzygaitOfflineTargets NAMESPACE fuzzygait:: DESTINATION ${package_dir}
        COMPONENT offline)

install(TARGETS fuzzygait_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT tools)
install(DIRECTORY controllers/ DESTINATION ${CMAKE_INSTALL_DATADIR}/fuzzygait/controllers
        COMPONENT tools)

configure_package_config_file(cmake/fuzzygaitConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/fuzzygaitConfig.cmake INSTALL_DESTINATION ${package_dir})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/fuzzygaitConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/fuzzygaitConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/fuzzygaitConfigVersion.cmake
        DESTINATION ${package_dir} COMPONENT runtime)

# The Python module and fuzzygait_dask (component python) into a site-packages folder under the
# prefix, Debian's layout by default: /usr/lib/python3/dist-packages is on Debian's python3's path
# (under /usr/local, set FUZZYGAIT_INSTALL_PYTHONDIR=lib/python3.11/dist-packages, or an absolute
# path).
# The Blender add-on (component blender) into share/fuzzygait/blender/fuzzygait_blender, told
# where the module went (_installed.py, written at install time for the prefix installed to).
set(FUZZYGAIT_INSTALL_PYTHONDIR "lib/python3/dist-packages" CACHE STRING
    "Where cmake --install puts the Python module: relative to the prefix, or absolute")
if(TARGET fuzzygait_python)
  install(TARGETS fuzzygait_python LIBRARY DESTINATION ${FUZZYGAIT_INSTALL_PYTHONDIR}
          COMPONENT python)
  # fuzzygait_dask beside it: training and walks on a Dask cluster (docs/python.md).
  install(DIRECTORY apps/python/fuzzygait_dask DESTINATION ${FUZZYGAIT_INSTALL_PYTHONDIR}
          COMPONENT python PATTERN __pycache__ EXCLUDE)
endif()
set(blender_addon_dir ${CMAKE_INSTALL_DATADIR}/fuzzygait/blender)
install(DIRECTORY apps/blender/fuzzygait_blender DESTINATION ${blender_addon_dir}
        COMPONENT blender PATTERN __pycache__ EXCLUDE)
if(TARGET fuzzygait_python)
  install(CODE "
    set(python_dir \"${FUZZYGAIT_INSTALL_PYTHONDIR}\")
    if(NOT IS_ABSOLUTE \"\${python_dir}\")
      set(python_dir \"\${CMAKE_INSTALL_PREFIX}/\${python_dir}\")
    endif()
    set(addon \"\$ENV{DESTDIR}\${CMAKE_INSTALL_PREFIX}/${blender_addon_dir}/fuzzygait_blender\")
    message(STATUS \"Installing: \${addon}/_installed.py\")
    file(WRITE \"\${addon}/_installed.py\"
         \"# Written by cmake --install: where it put the fuzzygait module.\\nMODULE_DIR = r'\${python_dir}'\\n\")
    " COMPONENT blender)
endif()
