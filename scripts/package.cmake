# SPDX-License-Identifier: GPL-3.0-or-later
# Installing the command and its deployment files, and the Debian packages
# made by CPack ('cpack -G DEB' in the build folder; docs/deployment.md).
# The library, its headers and swaywatch.pc are installed by src/lib, the
# manual pages by docs, the LCM definitions and bindings by lcmtypes.
#
# Two packages, as Debian splits a library, and a third for clusters:
#   swaywatch         the command (never linked with MPI: what a vehicle
#                     installs pulls in no cluster stack), libswaywatch.so.0,
#                     manual pages, bash completion, the systemd unit,
#                     example scenes and drives, LCM types and bindings;
#   libswaywatch-dev  headers, libswaywatch.a, the .so link, swaywatch.pc;
#   swaywatch-mpi     in a build with MPI (SW_MPI): swaywatch-mpi, the same
#                     command that runs batch and boundary over the ranks of
#                     mpirun or srun, and what it needs of Open MPI.
# Install rules without a COMPONENT land in swaywatch (see the default
# component set at the top of the top-level CMakeLists.txt).

install(TARGETS swaywatch-cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime)
if(TARGET swaywatch-mpi-cli)
  install(TARGETS swaywatch-mpi-cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT mpi)
  # its manual page is swaywatch's (the same options), by a .so link
  file(WRITE ${PROJECT_BINARY_DIR}/debian/swaywatch-mpi.1 ".so man1/swaywatch.1\n")
  install(FILES ${PROJECT_BINARY_DIR}/debian/swaywatch-mpi.1
          DESTINATION ${CMAKE_INSTALL_MANDIR}/man1 COMPONENT mpi)
endif()
install(FILES ${PROJECT_SOURCE_DIR}/scripts/bash-completion/swaywatch
        DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions COMPONENT runtime)
install(FILES ${PROJECT_SOURCE_DIR}/scripts/systemd/monitor.default
        DESTINATION ${CMAKE_INSTALL_DOCDIR}/examples COMPONENT runtime)
install(FILES ${PROJECT_SOURCE_DIR}/docs/deployment.md
        DESTINATION ${CMAKE_INSTALL_DOCDIR} COMPONENT runtime)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/examples/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/examples
        COMPONENT runtime FILES_MATCHING PATTERN "*.c" PATTERN "*.py" PATTERN "README*")
# The licence in Debian's machine-readable form (the full text is LICENSE in
# the source; Debian systems have it in /usr/share/common-licenses/GPL-3).
install(FILES ${PROJECT_SOURCE_DIR}/scripts/debian/copyright
        DESTINATION ${CMAKE_INSTALL_DOCDIR} COMPONENT runtime)
# Example scenes and the two sample drives the manual pages' EXAMPLES use,
# outside the doc folder: they are input to the commands, not reading.
install(FILES ${PROJECT_SOURCE_DIR}/sample_logs/crate.ini
              ${PROJECT_SOURCE_DIR}/sample_logs/crate-on-frame.ini
              ${PROJECT_SOURCE_DIR}/sample_logs/crate-on-cushion.ini
              ${PROJECT_SOURCE_DIR}/sample_logs/braking-pothole.csv
              ${PROJECT_SOURCE_DIR}/sample_logs/hard-stop-overturn.csv
        DESTINATION ${CMAKE_INSTALL_DATADIR}/swaywatch/examples COMPONENT runtime)

# LCM message definitions and the bindings lcmtypes/ generates, for
# consumers of the monitor's messages (C sources, Python modules, the jar
# for lcm-spy), all under share/swaywatch/lcmtypes.
if(TARGET swaywatch_lcmtypes)
  set(SW_LCM_DEST ${CMAKE_INSTALL_DATADIR}/swaywatch/lcmtypes)
  file(GLOB SW_LCM_DEFS ${PROJECT_SOURCE_DIR}/lcmtypes/*.lcm)
  get_target_property(SW_LCM_C_SOURCES swaywatch_lcmtypes SOURCES)
  list(FILTER SW_LCM_C_SOURCES INCLUDE REGEX "\\.c$")
  string(REGEX REPLACE "\\.c(;|$)" ".h\\1" SW_LCM_C_HEADERS "${SW_LCM_C_SOURCES}")
  install(FILES ${SW_LCM_DEFS} DESTINATION ${SW_LCM_DEST} COMPONENT runtime)
  install(FILES ${SW_LCM_C_SOURCES} ${SW_LCM_C_HEADERS} DESTINATION ${SW_LCM_DEST}/c
          COMPONENT runtime)
  if(SW_LCM_PYTHON_DIR)
    install(DIRECTORY ${SW_LCM_PYTHON_DIR}/swaywatch DESTINATION ${SW_LCM_DEST}/python
            COMPONENT runtime FILES_MATCHING PATTERN "*.py")
  endif()
  if(SW_LCM_JAVA_JAR)
    install(FILES ${SW_LCM_JAVA_JAR} DESTINATION ${SW_LCM_DEST}/java COMPONENT runtime)
  endif()
endif()

# Last of the runtime rules (install rules run in the order they are
# declared, and this file is included after every subdirectory), so that
# the library is in place: scripts/install.cmake installs the systemd unit
# with ExecStart naming PREFIX/bin/swaywatch, the prefix being the one given
# at install time (--prefix, CPack's /usr), and runs ldconfig where needed.
# The unit goes relative to the prefix, not LIBDIR: systemd looks in
# /usr/lib/systemd/system and /usr/local/lib/systemd/system, never in a
# multiarch folder.
install(CODE "
  set(SW_UNIT_IN \"${PROJECT_SOURCE_DIR}/scripts/systemd/swaywatch-monitor.service.in\")
  set(SW_UNIT_DIR lib/systemd/system)
  set(SW_BINDIR_REL \"${CMAKE_INSTALL_BINDIR}\")
  set(SW_LIBDIR_REL \"${CMAKE_INSTALL_LIBDIR}\")
  set(SW_WORK_DIR \"${PROJECT_BINARY_DIR}/scripts\")" COMPONENT runtime)
install(SCRIPT ${PROJECT_SOURCE_DIR}/scripts/install.cmake COMPONENT runtime)

# 'cmake --build build --target uninstall': removes what the last
# 'cmake --install build' installed (build/install_manifest.txt).
add_custom_target(uninstall
  COMMAND ${CMAKE_COMMAND} -DSW_MANIFEST=${PROJECT_BINARY_DIR}/install_manifest.txt
          -P ${PROJECT_SOURCE_DIR}/scripts/uninstall.cmake
  COMMENT "Removing the files of build/install_manifest.txt"
  VERBATIM)

set(SW_DEB_MAINTAINER "swaywatch developers <dev@swaywatch.invalid>"
    CACHE STRING "Maintainer field of the Debian packages")

set(CPACK_PACKAGE_NAME swaywatch)
set(CPACK_PACKAGE_VENDOR "swaywatch developers")
set(CPACK_PACKAGE_CONTACT "${SW_DEB_MAINTAINER}")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_GENERATOR DEB)
set(CPACK_COMPONENTS_ALL runtime dev)
if(TARGET swaywatch-mpi-cli)
  list(APPEND CPACK_COMPONENTS_ALL mpi)
endif()
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_RELEASE 1)
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "${SW_DEB_MAINTAINER}")
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
# Debian policy for what goes into a package, beyond what 'cmake --install'
# does for any prefix: stripped ELF files (CPack), and, in the staging folder
# of each package (scripts/debian/stage.cmake): manual pages compressed,
# /usr/share/doc/PACKAGE/copyright and changelog.Debian.gz.
set(CPACK_STRIP_FILES ON)
string(TIMESTAMP SW_DEB_DATE "%a, %d %b %Y %H:%M:%S +0000" UTC)   # honours SOURCE_DATE_EPOCH
configure_file(${PROJECT_SOURCE_DIR}/scripts/debian/changelog.in
               ${PROJECT_BINARY_DIR}/debian/changelog @ONLY)
set(CPACK_SW_DEB_CHANGELOG ${PROJECT_BINARY_DIR}/debian/changelog)
set(CPACK_SW_DEB_COPYRIGHT ${PROJECT_SOURCE_DIR}/scripts/debian/copyright)
# stage.cmake: the Debian packages; release-commit.cmake: the source
# tarball's COMMIT (each leaves the other's packages alone).
set(CPACK_PRE_BUILD_SCRIPTS ${PROJECT_SOURCE_DIR}/scripts/debian/stage.cmake
                            ${PROJECT_SOURCE_DIR}/scripts/release-commit.cmake)
set(CPACK_SW_SOURCE_DIR ${PROJECT_SOURCE_DIR})

# swaywatch: run-time dependencies from the ELF files (dpkg-shlibdeps, from
# dpkg-dev), a shlibs file and the ldconfig trigger for libswaywatch.so.0.
# The first line of each description is the package's synopsis (no
# CPACK_PACKAGE_DESCRIPTION_SUMMARY: CPack would put it in front of both).
set(CPACK_DEBIAN_RUNTIME_PACKAGE_NAME swaywatch)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_GENERATE_SHLIBS ON)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_RECOMMENDS "bash-completion")
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SUGGESTS "liblcm-bin, liblcm-java, python3")
set(CPACK_DEBIAN_RUNTIME_PACKAGE_CONTROL_EXTRA
    ${PROJECT_SOURCE_DIR}/scripts/debian/postinst
    ${PROJECT_SOURCE_DIR}/scripts/debian/prerm
    ${PROJECT_SOURCE_DIR}/scripts/debian/postrm
    ${PROJECT_SOURCE_DIR}/scripts/debian/triggers)
set(CPACK_DEBIAN_RUNTIME_DESCRIPTION
"tip-over watch for floating cargo on a truck
swaywatch reads the longitudinal acceleration of a truck bed (CSV logs,
lcm-logger logs or live LCM messages), advances a rocking model of each
package standing on the bed, on a support frame or on a cushion, and
reports the sway angle, a margin to overturn and alarms.
.
This package has the swaywatch command (replay, simulate, monitor, ...),
the shared library, a systemd unit for the live monitor, and the LCM
message definitions with their C, Java and Python bindings.")

# libswaywatch-dev: what building against the library needs, including the
# -dev packages named by swaywatch.pc (Requires.private, -lcsv).
set(CPACK_DEBIAN_DEV_PACKAGE_NAME libswaywatch-dev)
set(CPACK_DEBIAN_DEV_PACKAGE_SECTION libdevel)
set(CPACK_DEBIAN_DEV_PACKAGE_DEPENDS
    "swaywatch (= ${PROJECT_VERSION}-${CPACK_DEBIAN_PACKAGE_RELEASE}), libgsl-dev, libcsv-dev, libinih-dev, pkg-config")
set(CPACK_DEBIAN_DEV_DESCRIPTION
"tip-over watch for floating cargo on a truck - development files
The C11 library of swaywatch: scene files, rocking models, the streaming
engine and the CSV reader.  Headers, static library and swaywatch.pc:
  cc app.c $(pkg-config --cflags --libs swaywatch)")

# swaywatch-mpi: Open MPI's libraries found by dpkg-shlibdeps, and the
# swaywatch package for the library, data and manual pages.
set(CPACK_DEBIAN_MPI_PACKAGE_NAME swaywatch-mpi)
set(CPACK_DEBIAN_MPI_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_MPI_PACKAGE_DEPENDS
    "swaywatch (= ${PROJECT_VERSION}-${CPACK_DEBIAN_PACKAGE_RELEASE})")
set(CPACK_DEBIAN_MPI_PACKAGE_RECOMMENDS "openmpi-bin")
set(CPACK_DEBIAN_MPI_DESCRIPTION
"tip-over watch for floating cargo on a truck - MPI build for clusters
swaywatch-mpi is the swaywatch command built with MPI: under mpirun or
srun, 'swaywatch-mpi batch' and 'swaywatch-mpi boundary' share their work
among the ranks of the job, with the same output as one process.
.
For fleet analysis on a cluster; a vehicle needs only the swaywatch
package, which does not depend on MPI.")

set(CPACK_SOURCE_GENERATOR TGZ)
# .git is a file in a worktree: neither it nor a checkout's folder is packed.
set(CPACK_SOURCE_IGNORE_FILES "/\\\\.git/" "/\\\\.git$" "/build[^/]*/")
include(CPack)
