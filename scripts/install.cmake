# SPDX-License-Identifier: GPL-3.0-or-later
# Install-time steps that depend on the prefix given to 'cmake --install'
# (--prefix, or CPack's /usr), which is only known then: run by
# install(SCRIPT) from scripts/package.cmake, after every other install rule
# of the runtime component, with SW_UNIT_IN, SW_UNIT_DIR, SW_BINDIR_REL,
# SW_LIBDIR_REL and SW_WORK_DIR set by an install(CODE) before it.
#
#  - The systemd unit, with ExecStart naming this installation's swaywatch
#    by its full path (PREFIX/bin/swaywatch).
#  - ldconfig, for a library installed in a folder of the linker's cache.

include(${CMAKE_CURRENT_LIST_DIR}/ldconfig.cmake)

function(sw_abs var rel)   # a GNUInstallDirs folder, relative to the prefix or absolute
  if(IS_ABSOLUTE "${rel}")
    set(${var} "${rel}" PARENT_SCOPE)
  else()
    set(${var} "${CMAKE_INSTALL_PREFIX}/${rel}" PARENT_SCOPE)
  endif()
endfunction()

sw_abs(SW_BINDIR "${SW_BINDIR_REL}")
if(SW_BINDIR MATCHES "[ \t'\"$\\\\%]")
  message(FATAL_ERROR "The systemd unit cannot name '${SW_BINDIR}/swaywatch': the "
                      "installation folder must not contain blanks, quotes, '$', '%' or '\\'")
endif()
# A private folder per run: 'cmake --install' to two prefixes may run at once.
string(RANDOM LENGTH 12 tag)
set(tmp "${SW_WORK_DIR}/unit-${tag}")
configure_file("${SW_UNIT_IN}" "${tmp}/swaywatch-monitor.service" @ONLY)
# file(INSTALL) as the generated rules do: DESTDIR, the message, the manifest.
file(INSTALL DESTINATION "${CMAKE_INSTALL_PREFIX}/${SW_UNIT_DIR}" TYPE FILE
     FILES "${tmp}/swaywatch-monitor.service")
file(REMOVE_RECURSE "${tmp}")

sw_abs(SW_LIBDIR "${SW_LIBDIR_REL}")
sw_ldconfig("${SW_LIBDIR}" install)
