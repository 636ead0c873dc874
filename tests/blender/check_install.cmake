# Installs the Python module (with fuzzygait_dask) and the Blender add-on (components python and
# blender) into a scratch prefix, then has Blender walk an armature with the installed add-on,
# given neither the module's folder nor the build tree: the add-on finds the module where the
# install put it.
# cmake -DBLENDER=... -DBUILD_DIR=... -DSCRIPT=... -DCLI=... -DDATADIR=... -DWORK_DIR=...
#       -P check_install.cmake
file(REMOVE_RECURSE "${WORK_DIR}")
set(prefix "${WORK_DIR}/prefix")

include(${CMAKE_CURRENT_LIST_DIR}/../install/run_command.cmake)  # run(COMMAND...)

foreach(component IN ITEMS python blender)
  run(${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${prefix}" --component ${component})
endforeach()
file(GLOB_RECURSE modules "${prefix}/*/fuzzygait.cpython-*.so")
set(addon "${prefix}/${DATADIR}/fuzzygait/blender")
if(modules)
  list(GET modules 0 module)
  get_filename_component(python_dir "${module}" DIRECTORY)
endif()
if(NOT modules OR NOT EXISTS "${python_dir}/fuzzygait_dask/__init__.py" OR NOT EXISTS "${addon}/fuzzygait_blender/__init__.py"
   OR NOT EXISTS "${addon}/fuzzygait_blender/_installed.py")
  file(GLOB_RECURSE installed RELATIVE "${prefix}" "${prefix}/*")
  message(FATAL_ERROR "the module, fuzzygait_dask or the add-on is not installed: ${installed}")
endif()
run("${BLENDER}" -b --factory-startup --python-exit-code 1 --python "${SCRIPT}" --
    --addon-dir "${addon}" --cli "${CLI}" --work "${WORK_DIR}/work" straight)
if(NOT run_output MATCHES "fuzzygait module: ${prefix}/")
  message(FATAL_ERROR "the add-on did not take the installed module:\n${run_output}")
endif()
message(STATUS "the installed add-on walks with the installed module (${modules}):\n"
               "${run_output}")
