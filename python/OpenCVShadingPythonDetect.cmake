# Finds pybind11 for the Python the module is built for; included by the top CMakeLists.txt so
# OPENCV_SHADING_BUILD_PYTHON can default to whether it was found.
#
# Debian's /usr/bin/python3 is the default even when another python3 (pyenv, conda) comes first
# on PATH: Debian's python3-numpy, python3-opencv and pybind11-dev belong to it. Override with
# -DPython_EXECUTABLE=/path/to/python3.
if(NOT DEFINED Python_EXECUTABLE)
  if(DEFINED PYTHON_EXECUTABLE)  # pybind11's classic spelling, given by the user
    set(Python_EXECUTABLE ${PYTHON_EXECUTABLE} CACHE FILEPATH "Python the module is built for")
  elseif(EXISTS /usr/bin/python3)
    set(Python_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "Python the module is built for")
  endif()
endif()
if(DEFINED Python_EXECUTABLE AND NOT DEFINED PYTHON_EXECUTABLE)
  # pybind11's classic FindPythonLibsNew path reads the upper-case name.
  set(PYTHON_EXECUTABLE ${Python_EXECUTABLE} CACHE FILEPATH "Same as Python_EXECUTABLE")
endif()

set(OPENCV_SHADING_PYBIND11_FOUND OFF)
find_package(Python COMPONENTS Interpreter Development.Module QUIET)
if(Python_FOUND)
  find_package(pybind11 2.6 CONFIG QUIET)
  if(pybind11_FOUND)
    set(OPENCV_SHADING_PYBIND11_FOUND ON)
  else()
    message(STATUS "opencv_shading: pybind11 not found, Python module not built "
                   "(Debian: apt-get install pybind11-dev python3-numpy)")
  endif()
else()
  message(STATUS "opencv_shading: no Python interpreter with development headers found, "
                 "Python module not built (Debian: apt-get install python3-dev pybind11-dev)")
endif()
