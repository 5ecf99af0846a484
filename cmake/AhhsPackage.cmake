# Debian packages with CPack (docs/install.md): `cpack --config BUILD/CPackConfig.cmake` makes
#   ahhs-module_VERSION_ARCH.deb  a module board: ahhs-module and the Lua reference controller
#   ahhs_VERSION_ARCH.deb         a lab PC: every tool, the viewer, the report, the Python
#                                 package, message types and bindings, libraries and their CMake
#                                 and pkg-config files, docs; depends on ahhs-module.
# Shared-library dependencies come from dpkg-shlibdeps; the rest are named here.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME ahhs)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_VENDOR "AHHS")
set(AHHS_PACKAGE_CONTACT "AHHS maintainers <maintainers@ahhs.example.org>" CACHE STRING
    "the Maintainer of the Debian packages (a lab that builds its own puts its own here)")
set(CPACK_PACKAGE_CONTACT "${AHHS_PACKAGE_CONTACT}")
set(CPACK_STRIP_FILES ON)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL module lab)
if(AHHS_MODULE_ONLY)
  set(CPACK_COMPONENTS_ALL module)
endif()
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)

set(CPACK_DEBIAN_MODULE_PACKAGE_NAME ahhs-module)
set(CPACK_COMPONENT_MODULE_DESCRIPTION
    "AHHS hormone controller for one module of a modular robot\n\
ahhs-module runs one module's artificial homeostatic hormone system (AHHS1 or\n\
AHHS2) as an LCM node: sensors in, hinge commands and hormone packets out.\n\
The package also has the Lua 5.2 reference controller. It is what a module\n\
board needs; the lab PC takes the ahhs package.")
set(CPACK_DEBIAN_MODULE_PACKAGE_DEPENDS "lua5.2, liblcm-lua, lua-posix")
# A cross build (cmake/toolchains) names the board's architecture; dpkg-shlibdeps cannot read
# the cross libraries there, so the shared libraries are named as the native build finds them.
if(CMAKE_CROSSCOMPILING)
  if(NOT AHHS_DEB_ARCHITECTURE)
    message(FATAL_ERROR "a cross build needs AHHS_DEB_ARCHITECTURE (set by cmake/toolchains/*)")
  endif()
  set(CPACK_DEBIAN_PACKAGE_ARCHITECTURE ${AHHS_DEB_ARCHITECTURE})
  set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS OFF)
  set(CPACK_DEBIAN_MODULE_PACKAGE_DEPENDS
      "lua5.2, liblcm-lua, lua-posix, libc6 (>= 2.34), libgcc-s1 (>= 3.0), libglib2.0-0 (>= 2.59.0), liblcm1, libstdc++6 (>= 11)")
endif()

set(CPACK_DEBIAN_LAB_PACKAGE_NAME ahhs)
set(CPACK_COMPONENT_LAB_DESCRIPTION
    "evolving artificial hormone controllers for modular robots\n\
AHHS evolves artificial homeostatic hormone systems (AHHS1, AHHS2) for\n\
multi-modular robots. Module controllers, an ODE simulator, a fitness monitor\n\
and an evolver are separate processes that talk LCM, so any of them can be\n\
replaced by hardware. The package has every tool (ahhs-evolve, ahhs-launch,\n\
ahhs-view, ahhs-report, ahhs-study, ...), the message types with their\n\
bindings, the Python package and the libraries for programs of your own.")
set(CPACK_DEBIAN_LAB_PACKAGE_DEPENDS
    "ahhs-module (= ${PROJECT_VERSION}), python3, python3-numpy, python3-scipy, python3-matplotlib, libjs-three, iproute2")
set(CPACK_DEBIAN_LAB_PACKAGE_RECOMMENDS
    "chromium, ffmpeg, python3-pil, fonts-dejavu-core, liblcm-dev, libglib2.0-dev, libeigen3-dev, nlohmann-json3-dev, pkg-config")
set(CPACK_DEBIAN_LAB_PACKAGE_SUGGESTS "slurm-wlm, default-jre, liblcm-java, libjchart2d-java, nftables")

# Each package's /usr/share/doc/PACKAGE: the copyright file, and CHANGELOG.md as changelog.gz.
set(changelog_gz ${PROJECT_BINARY_DIR}/packaging/changelog.gz)
add_custom_command(
  OUTPUT ${changelog_gz}
  COMMAND ${CMAKE_COMMAND} -E make_directory ${PROJECT_BINARY_DIR}/packaging
  COMMAND sh -c "gzip -9n -c '${PROJECT_SOURCE_DIR}/CHANGELOG.md' > '${changelog_gz}'"
  DEPENDS ${PROJECT_SOURCE_DIR}/CHANGELOG.md
  VERBATIM)
add_custom_target(ahhs_package_changelog ALL DEPENDS ${changelog_gz})
install(FILES ${PROJECT_SOURCE_DIR}/packaging/copyright ${changelog_gz}
        DESTINATION ${CMAKE_INSTALL_DOCDIR} COMPONENT lab)
install(FILES ${PROJECT_SOURCE_DIR}/packaging/copyright ${changelog_gz}
        DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/ahhs-module COMPONENT module)
include(CPack)
