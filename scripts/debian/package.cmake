# What `cmake --install` puts beside the programs, and the Debian package CPack makes of it
# (scripts/package.sh builds it; docs/packaging.md says what is in it and why). Included by the
# top-level CMakeLists.txt after the programs' own install rules.

# RIGSIM_DEBIAN_LAYOUT (scripts/package.sh turns it on): the layout of the Debian package, prefix
# /usr: the Python package in Debian's python3 path (lib/python3/dist-packages) instead of
# lib/rigsim/python, and /etc/rigsim/default.json, the rig rigsim@default.service runs.
option(RIGSIM_DEBIAN_LAYOUT "Install for the Debian package (scripts/package.sh): Python package in lib/python3/dist-packages, /etc/rigsim/default.json" OFF)
if(RIGSIM_DEBIAN_LAYOUT)
  set(RIGSIM_INSTALL_PYTHONDIR lib/python3/dist-packages)
else()
  set(RIGSIM_INSTALL_PYTHONDIR lib/rigsim/python)
endif()
install(DIRECTORY python/rigsim DESTINATION ${RIGSIM_INSTALL_PYTHONDIR} PATTERN __pycache__ EXCLUDE)
# Its .dist-info (pytest finds the plugin by its entry point), from python/pyproject.toml.
set(rigsim_dist_info ${CMAKE_CURRENT_BINARY_DIR}/generated/dist-info)
add_custom_command(OUTPUT ${rigsim_dist_info}/rigsim-${PROJECT_VERSION}.dist-info/METADATA
  COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/scripts/debian/dist_info.py ${rigsim_dist_info}
  DEPENDS ${PROJECT_SOURCE_DIR}/python/pyproject.toml ${PROJECT_SOURCE_DIR}/scripts/debian/dist_info.py
  COMMENT "rigsim.dist-info from python/pyproject.toml" VERBATIM)

# The man pages, as docs/man/ holds them (scripts/make_man.py writes them from --help and
# docs/config.md; CTest's docs_man_pages fails when they drift), compressed as Debian installs them.
set(rigsim_man_pages rigsimd.1 rigsimctl.1 rigsim-rig.5)
set(rigsim_man_outputs)
foreach(page ${rigsim_man_pages})
  set(compressed ${CMAKE_CURRENT_BINARY_DIR}/generated/man/${page}.gz)
  add_custom_command(OUTPUT ${compressed}
    COMMAND gzip -9 -n -c ${PROJECT_SOURCE_DIR}/docs/man/${page} > ${compressed}
    DEPENDS ${PROJECT_SOURCE_DIR}/docs/man/${page} VERBATIM)
  list(APPEND rigsim_man_outputs ${compressed})
  string(REGEX MATCH "[0-9]$" section ${page})
  install(FILES ${compressed} DESTINATION share/man/man${section})
endforeach()
file(MAKE_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}/generated/man)
add_custom_target(rigsim_install_files ALL
  DEPENDS ${rigsim_man_outputs} ${rigsim_dist_info}/rigsim-${PROJECT_VERSION}.dist-info/METADATA)
install(DIRECTORY ${rigsim_dist_info}/ DESTINATION ${RIGSIM_INSTALL_PYTHONDIR})

# The rigs: the built-in default (compiled into rigsimd; this copy is to read and start from),
# the examples and the stage files (also compiled in).
install(FILES config/default.json DESTINATION share/rigsim)
install(DIRECTORY config/examples config/stages DESTINATION share/rigsim)

# bash completion, one file per program (bash-completion loads a command's file by its name).
foreach(program rigsimd rigsimctl rigsim-replay)
  install(FILES scripts/debian/completion.bash DESTINATION share/bash-completion/completions RENAME ${program})
endforeach()

# The systemd template unit: rigsim@NAME runs /etc/rigsim/NAME.json.
install(FILES scripts/debian/rigsim@.service DESTINATION lib/systemd/system)
if(RIGSIM_DEBIAN_LAYOUT)
  install(FILES config/default.json DESTINATION /etc/rigsim)
endif()

# ---- CPack: rigsim_<version>_<arch>.deb ----
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME rigsim)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "emulator of SmarAct MCS/MCS2 and Thorlabs APT motion controllers")
set(CPACK_PACKAGE_DESCRIPTION "rigsimd emulates SmarAct MCS and MCS2 and Thorlabs APT motion controllers on
pseudo-terminals, TCP sockets and RFC 2217 serial ports, so that unmodified drivers and
applications run against a virtual rig described in one JSON file; an HTTP control API
steers its clock, faults and state. Includes rigsimctl, rigsim-tap, rigsim-replay, the
rigsim Python package and pytest plugin, and the systemd unit rigsim@.service.")
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "rigsim developers <rigsim-dev@localhost>")
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
# Libraries by dpkg-shlibdeps (spdlog, fmt, libstdc++), Python for rigsimctl and rigsim-replay.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "python3 (>= 3.9)")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "python3-serial, python3-pytest")
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA
  ${PROJECT_SOURCE_DIR}/scripts/debian/conffiles ${PROJECT_SOURCE_DIR}/scripts/debian/postinst
  ${PROJECT_SOURCE_DIR}/scripts/debian/prerm ${PROJECT_SOURCE_DIR}/scripts/debian/postrm)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
set(CPACK_OUTPUT_FILE_PREFIX ${CMAKE_CURRENT_BINARY_DIR}/package)
include(CPack)
