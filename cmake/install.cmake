# `cmake --install` and CPack (README, "Install"): the CLI, the module libraries and their public
# headers, a CMake package (find_package(jellysim) -> jellysim::<module>), the Python module in
# Debian's site directory, the scenes and the Blender add-on zip. Two components, two .deb files:
# runtime (jellysim_*.deb: CLI, Python module, scenes, add-on) and development (jellysim-dev_*.deb).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# Every module but the viewer (the CLI's window: GLFW and Dear ImGui, which no library user needs).
get_property(jellysim_modules GLOBAL PROPERTY JELLYSIM_MODULES)
list(REMOVE_ITEM jellysim_modules viewer)
list(TRANSFORM jellysim_modules PREPEND jellysim_ OUTPUT_VARIABLE jellysim_module_targets)
set_target_properties(jellysim_lib PROPERTIES EXPORT_NAME lib)
install(TARGETS ${jellysim_module_targets} jellysim_lib EXPORT jellysimTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT development
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/jellysim DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        COMPONENT development PATTERN "viewer" EXCLUDE)
set(JELLYSIM_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/jellysim)
install(EXPORT jellysimTargets NAMESPACE jellysim:: DESTINATION ${JELLYSIM_CMAKE_DIR} COMPONENT development)
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/jellysimConfig.cmake.in
                              ${CMAKE_BINARY_DIR}/jellysimConfig.cmake INSTALL_DESTINATION ${JELLYSIM_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_BINARY_DIR}/jellysimConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/jellysimConfig.cmake ${CMAKE_BINARY_DIR}/jellysimConfigVersion.cmake
        DESTINATION ${JELLYSIM_CMAKE_DIR} COMPONENT development)

install(TARGETS jellysim RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/scenes/ DESTINATION ${CMAKE_INSTALL_DATADIR}/jellysim/scenes COMPONENT runtime)
# viewer.html's script (render::default_viewer_script finds it here when the source tree is gone).
install(FILES ${PROJECT_SOURCE_DIR}/web/dist/jellyfish-viewer.js DESTINATION ${CMAKE_INSTALL_DATADIR}/jellysim/web
        COMPONENT runtime)
# Debian's interpreter reads /usr/lib/python3/dist-packages (and /usr/local/lib/python3.11/dist-packages):
# under the prefix /usr (the .deb) `import jellysim` needs no PYTHONPATH; another prefix needs
# PYTHONPATH=<prefix>/lib/python3/dist-packages.
set(JELLYSIM_PYTHON_INSTALL_DIR lib/python3/dist-packages CACHE STRING "Where the Python module is installed (under the prefix)")
if(TARGET jellysim_python)
  install(TARGETS jellysim_python LIBRARY DESTINATION ${JELLYSIM_PYTHON_INSTALL_DIR} COMPONENT runtime)
endif()
if(TARGET jellysim_blender_zip)
  install(FILES ${JELLYSIM_BLENDER_ZIP} DESTINATION ${CMAKE_INSTALL_DATADIR}/jellysim COMPONENT runtime)
endif()

# The installed tree works: examples/ configured and built against it through find_package(jellysim),
# one example run, and the installed Python module imported (tests/install/installed_tree_test.sh).
# Not in the sanitizer builds: their link flags are not part of the exported targets.
if(BUILD_TESTING AND NOT JELLYSIM_SANITIZE AND NOT JELLYSIM_TSAN)
  add_test(NAME Install.ExamplesAgainstInstalledTree
           COMMAND bash ${PROJECT_SOURCE_DIR}/tests/install/installed_tree_test.sh ${CMAKE_BINARY_DIR}
                   ${PROJECT_SOURCE_DIR}/examples ${CMAKE_COMMAND} ${Python3_EXECUTABLE})
  set_tests_properties(Install.ExamplesAgainstInstalledTree PROPERTIES TIMEOUT 300 RUN_SERIAL TRUE)
endif()

# `cpack -G DEB` (in the build folder): jellysim_VERSION_ARCH.deb and jellysim-dev_VERSION_ARCH.deb.
set(CPACK_PACKAGE_NAME jellysim)
set(CPACK_PACKAGE_VENDOR "jellysim")
set(CPACK_PACKAGE_CONTACT "jellysim maintainers <jellysim@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Physically simulated jellyfish: CLI, Python module, Blender add-on")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_GENERATOR DEB)
set(CPACK_COMPONENTS_ALL runtime development)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_NAME jellysim)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SECTION science)
# The shared libraries the CLI and the Python module load (dpkg-shlibdeps), plus what they run:
# the interpreter and NumPy for the module, ffmpeg for videos, Mesa for offscreen rendering.
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_DEPENDS "python3 (>= 3.11), python3 (<< 3.12), python3-numpy, libegl-mesa0, libgl1-mesa-dri, plplot-driver-cairo, fonts-dejavu-core")
set(CPACK_DEBIAN_RUNTIME_PACKAGE_RECOMMENDS "ffmpeg, blender")
set(CPACK_DEBIAN_DEVELOPMENT_PACKAGE_NAME jellysim-dev)
set(CPACK_DEBIAN_DEVELOPMENT_PACKAGE_SECTION libdevel)
set(CPACK_DEBIAN_DEVELOPMENT_PACKAGE_DEPENDS
    "jellysim (= ${PROJECT_VERSION}), cmake (>= 3.25), pkg-config, libeigen3-dev, nlohmann-json3-dev, libtomlplusplus-dev, zlib1g-dev, libpng-dev, libopenexr-dev, libcereal-dev, libegl-dev, libopengl-dev, libfftw3-dev, libplplot-dev")
include(CPack)
