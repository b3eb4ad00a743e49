# Finds pybind11 and Python 3 (interpreter, headers, NumPy) for the Python module (python/):
# JELLYSIM_PYTHON AUTO builds it when they are found, ON requires them, OFF skips it. AUTO skips it
# in the sanitizer build (an instrumented module in an uninstrumented interpreter; docs/python.md).
if(JELLYSIM_SANITIZE AND JELLYSIM_PYTHON STREQUAL "AUTO")
  set(JELLYSIM_PYTHON OFF)
endif()
if(NOT JELLYSIM_PYTHON STREQUAL "OFF")
  # Debian's interpreter has Debian's python3-numpy and python3-pytest; prefer it to another python3
  # earlier on PATH (e.g. pyenv's) unless one is named with -DPython3_EXECUTABLE=...
  if(NOT DEFINED Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
    set(Python3_EXECUTABLE /usr/bin/python3)
  endif()
  set(required)
  if(JELLYSIM_PYTHON STREQUAL "ON")
    set(required REQUIRED)
  endif()
  find_package(Python3 COMPONENTS Interpreter Development.Module NumPy ${required})
  find_package(pybind11 CONFIG ${required})
  if(Python3_FOUND AND Python3_NumPy_FOUND AND pybind11_FOUND)
    message(STATUS "jellysim: building the Python module with ${Python3_EXECUTABLE} (${Python3_VERSION})")
    add_subdirectory(python)
  else()
    message(STATUS "jellysim: no Python module (needs pybind11-dev, python3-dev, python3-numpy)")
  endif()
endif()
