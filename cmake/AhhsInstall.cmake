# Installation (docs/install.md): `cmake --install BUILD [--prefix P] [--component C]` and the
# Debian packages made from it (cmake/AhhsPackage.cmake). Two components:
#   module  what a module board needs: ahhs-module and the Lua reference controller with its
#           message types (package ahhs-module);
#   lab     everything else a lab PC runs (package ahhs, which depends on ahhs-module).
# Installed tools find their shared files in ../share/ahhs from their own directory
# (base::DataDir, the wrappers' `here`), so an installed tree can move. The build tree gets the
# same layout: build/share/ahhs links to the sources, so the tools run alike from both.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)
set(AHHS_DATA ${CMAKE_INSTALL_DATADIR}/ahhs)
set(src ${PROJECT_SOURCE_DIR})

# The build tree's share/ahhs: links to the sources and the generated Lua types.
set(build_share ${PROJECT_BINARY_DIR}/share/ahhs)
file(MAKE_DIRECTORY ${build_share})
foreach(link_target IN ITEMS "web=${src}/tools/view/web" "report=${src}/tools/report"
                             "view=${src}/tools/view" "configs=${src}/configs"
                             "studies=${src}/studies" "controller-lua=${src}/examples/controller-lua"
                             "lua=${AHHS_LUA_TYPES_DIR}")
  string(REPLACE "=" ";" pair "${link_target}")
  list(GET pair 0 name)
  list(GET pair 1 target)
  if(NOT IS_SYMLINK ${build_share}/${name})
    file(CREATE_LINK ${target} ${build_share}/${name} SYMBOLIC)
  endif()
endforeach()

# --- module: a module board ----------------------------------------------------------------
install(TARGETS ahhs-module RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT module)
install(PROGRAMS ${PROJECT_BINARY_DIR}/bin/ahhs-example-controller-lua
        DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT module)
install(FILES ${src}/examples/controller-lua/module.lua ${src}/examples/controller-lua/ahhs_model.lua
        DESTINATION ${AHHS_DATA}/controller-lua COMPONENT module)
install(DIRECTORY ${AHHS_LUA_TYPES_DIR}/ DESTINATION ${AHHS_DATA}/lua COMPONENT module)

if(AHHS_MODULE_ONLY)
  return()
endif()

# --- lab: the tools ------------------------------------------------------------------------
set(AHHS_LAB_PROGRAMS ahhs-bench ahhs-conformance ahhs-evaluate ahhs-evolve ahhs-fitness
                      ahhs-genome ahhs-launch ahhs-logger ahhs-replay ahhs-sim ahhs-study
                      ahhs-view ahhs-worker)
install(TARGETS ${AHHS_LAB_PROGRAMS} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT lab)
# Scripts: the Python wrappers as made for the build tree (they are relocatable), and the shell
# tools with their version filled in.
foreach(script ahhs-netns ahhs-spy)
  configure_file(${src}/tools/${script} ${PROJECT_BINARY_DIR}/install-scripts/${script} @ONLY)
endforeach()
install(PROGRAMS ${PROJECT_BINARY_DIR}/bin/ahhs-report ${PROJECT_BINARY_DIR}/bin/ahhs-capture
                 ${PROJECT_BINARY_DIR}/install-scripts/ahhs-netns
                 ${PROJECT_BINARY_DIR}/install-scripts/ahhs-spy
        DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT lab)
install(DIRECTORY ${src}/tools/view/web/ DESTINATION ${AHHS_DATA}/web COMPONENT lab)
install(DIRECTORY ${src}/tools/report/ DESTINATION ${AHHS_DATA}/report COMPONENT lab
        FILES_MATCHING PATTERN "*.py")
install(FILES ${src}/tools/view/ahhs_capture.py DESTINATION ${AHHS_DATA}/view COMPONENT lab)
install(DIRECTORY ${src}/configs/ DESTINATION ${AHHS_DATA}/configs COMPONENT lab)
# The plans and their scripts, not the studies' exported results (folders beside them).
file(GLOB study_plans CONFIGURE_DEPENDS ${src}/studies/*.toml ${src}/studies/*.py)
install(FILES ${study_plans} DESTINATION ${AHHS_DATA}/studies COMPONENT lab)
install(FILES ${src}/tools/conformance/data/model-vectors.txt DESTINATION ${AHHS_DATA}/conformance
        COMPONENT lab)

# The message types: definitions and their C, C++, Java, Lua (above) and Python bindings.
install(FILES ${AHHS_LCM_FILES} DESTINATION ${AHHS_DATA}/lcmtypes COMPONENT lab)
install(DIRECTORY ${AHHS_LCMTYPES_C_DIR}/ DESTINATION ${AHHS_DATA}/lcmtypes/c COMPONENT lab
        FILES_MATCHING PATTERN "*.c" PATTERN "*.h")
install(DIRECTORY ${AHHS_LCMTYPES_CPP_DIR}/ahhs DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/ahhs
        COMPONENT lab)
if(TARGET ahhs_lcmtypes_jar)
  install(FILES ${AHHS_LCMTYPES_JAR} DESTINATION ${AHHS_DATA}/java COMPONENT lab)
endif()

# Python: the ahhs package (python/ahhs) with the message types as its modules (ahhs.genome_t).
set(AHHS_PYTHON_DIR lib/python3/dist-packages CACHE STRING "where the ahhs Python package goes")
install(DIRECTORY ${src}/python/ahhs DESTINATION ${AHHS_PYTHON_DIR} COMPONENT lab
        FILES_MATCHING PATTERN "*.py")
install(DIRECTORY ${AHHS_LCMTYPES_PYTHON_DIR}/ DESTINATION ${AHHS_PYTHON_DIR}/ahhs COMPONENT lab
        FILES_MATCHING PATTERN "*_t.py")

# Libraries for other programs: find_package(ahhs CONFIG) gives ahhs::controller, ahhs::bus,
# ahhs::lcmtypes (and ahhs::base, which the first needs); pkg-config gives ahhs.
install(TARGETS ahhs_modules_core ahhs_bus ahhs_base ahhs_lcmtypes ahhs_warnings EXPORT ahhsTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT lab)
set_target_properties(ahhs_warnings PROPERTIES EXPORT_NAME warnings)
foreach(header_dir base bus modules/core)
  install(DIRECTORY ${src}/${header_dir}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/ahhs/${header_dir}
          COMPONENT lab FILES_MATCHING PATTERN "*.h")
endforeach()
set(AHHS_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/ahhs)
install(EXPORT ahhsTargets NAMESPACE ahhs:: DESTINATION ${AHHS_CMAKE_DIR} COMPONENT lab)
configure_package_config_file(${src}/cmake/ahhsConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/cmake/ahhsConfig.cmake
                              INSTALL_DESTINATION ${AHHS_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/cmake/ahhsConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/cmake/ahhsConfig.cmake
              ${PROJECT_BINARY_DIR}/cmake/ahhsConfigVersion.cmake
        DESTINATION ${AHHS_CMAKE_DIR} COMPONENT lab)
file(RELATIVE_PATH AHHS_PC_TO_PREFIX /p/${CMAKE_INSTALL_LIBDIR}/pkgconfig /p)
configure_file(${src}/cmake/ahhs.pc.in ${PROJECT_BINARY_DIR}/cmake/ahhs.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/cmake/ahhs.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig
        COMPONENT lab)

# Documentation, and a manual page per tool made from its --help and --version (help2man).
install(FILES ${src}/README.md ${src}/CHANGELOG.md DESTINATION ${CMAKE_INSTALL_DOCDIR}
        COMPONENT lab)
install(DIRECTORY ${src}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR} COMPONENT lab)
install(DIRECTORY ${src}/examples/downstream ${src}/examples/firmware-c ${src}/examples/tracker-c
                  ${src}/examples/optimizers
        DESTINATION ${CMAKE_INSTALL_DOCDIR}/examples COMPONENT lab)
find_program(HELP2MAN help2man)
if(HELP2MAN AND NOT CMAKE_CROSSCOMPILING AND NOT AHHS_SANITIZE)
  set(lab_pages "")
  set(name_ahhs-report "figures and summaries of ahhs-evolve runs and studies")
  set(name_ahhs-capture "screenshots, videos and filmstrips of ahhs-view's page in headless Chromium")
  foreach(program IN LISTS AHHS_LAB_PROGRAMS ITEMS ahhs-module ahhs-report ahhs-capture)
    set(page ${PROJECT_BINARY_DIR}/man/${program}.1.gz)
    if(TARGET ${program})
      set(exe $<TARGET_FILE:${program}>)
      set(deps ${program})
    else()
      set(exe ${PROJECT_BINARY_DIR}/bin/${program})
      set(deps ${exe})
    endif()
    add_custom_command(
      OUTPUT ${page}
      COMMAND ${CMAKE_COMMAND} -E make_directory ${PROJECT_BINARY_DIR}/man
      COMMAND ${src}/cmake/man_page.sh ${exe} ${page} ${name_${program}}
      DEPENDS ${deps} ${src}/cmake/man_page.sh
      VERBATIM)
    if(NOT program STREQUAL "ahhs-module")
      list(APPEND lab_pages ${page})
    endif()
  endforeach()
  add_custom_target(ahhs_man_pages ALL DEPENDS ${lab_pages} ${PROJECT_BINARY_DIR}/man/ahhs-module.1.gz)
  install(FILES ${lab_pages} DESTINATION ${CMAKE_INSTALL_MANDIR}/man1 COMPONENT lab)
  install(FILES ${PROJECT_BINARY_DIR}/man/ahhs-module.1.gz DESTINATION ${CMAKE_INSTALL_MANDIR}/man1
          COMPONENT module)
else()
  message(STATUS "AHHS: no manual pages (help2man missing, a cross build, or a sanitizer build)")
endif()
