# Installs the build tree into a fresh prefix, then checks the module from there with PYTHON.
# Arguments: BUILD_DIR, WORK_DIR (scratch), PYTHON, REL_DIR (module folder under the prefix),
# CHECK (check_install.py).
file(REMOVE_RECURSE ${WORK_DIR})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed (${rc}):\n${out}")
endif()
# -I: no PYTHONPATH, no user site, no current directory; only what the prefix provides.
execute_process(COMMAND ${PYTHON} -I ${CHECK} ${WORK_DIR}/prefix ${REL_DIR}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
message(STATUS "${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "installed module check failed (${rc})")
endif()
