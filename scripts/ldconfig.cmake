# SPDX-License-Identifier: GPL-3.0-or-later
# sw_ldconfig(LIBDIR WHAT): after 'cmake --install' (WHAT = install) or the
# uninstall target (WHAT = uninstall) changed libswaywatch.so.0 in LIBDIR,
# refresh the dynamic linker's cache when LIBDIR is one of the folders it
# caches (/usr/local/lib on Debian: not searched without the cache), so that
# programs linked to the library find it at once.  Runs ldconfig only as
# root and only for a live install (no DESTDIR: a staged tree, e.g. CPack's,
# is not on this system; the Debian package has its own ldconfig trigger).
# Otherwise it says what to do.  Included by scripts/install.cmake and
# scripts/uninstall.cmake.

function(sw_ldconfig libdir what)
  if(NOT "$ENV{DESTDIR}" STREQUAL "")
    return()
  endif()
  find_program(SW_LDCONFIG ldconfig PATHS /sbin /usr/sbin NO_CACHE)
  if(NOT SW_LDCONFIG)
    message(STATUS "No ldconfig here: programs linked to libswaywatch.so.0 find it only with "
                   "LD_LIBRARY_PATH=${libdir}")
    return()
  endif()
  # The folders ldconfig caches, one "DIR: (from FILE:LINE)" line each
  # (-N -X: read the configuration only, change nothing).
  execute_process(COMMAND ${SW_LDCONFIG} -v -N -X OUTPUT_VARIABLE out ERROR_QUIET)
  get_filename_component(dir "${libdir}" REALPATH)
  set(cached 0)
  string(REPLACE "\n" ";" lines "${out}")
  foreach(line IN LISTS lines)
    if(line MATCHES "^([^\t ][^:]*):")
      get_filename_component(d "${CMAKE_MATCH_1}" REALPATH)
      if(d STREQUAL dir)
        set(cached 1)
      endif()
    endif()
  endforeach()
  if(NOT cached)
    message(STATUS "${libdir} is not a folder of the dynamic linker's cache: programs linked "
                   "to libswaywatch.so.0 need LD_LIBRARY_PATH=${libdir}, or the folder in "
                   "/etc/ld.so.conf.d/ and 'ldconfig' as root")
    return()
  endif()
  execute_process(COMMAND id -u OUTPUT_VARIABLE uid OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(NOT uid STREQUAL "0")
    message(STATUS "Not root: run 'sudo ldconfig' so that programs find the ${what}ed "
                   "libswaywatch.so.0 in ${libdir}")
    return()
  endif()
  message(STATUS "Running: ldconfig (${libdir} is in the dynamic linker's cache)")
  execute_process(COMMAND ${SW_LDCONFIG} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(WARNING "ldconfig failed (${rc}): run it again as root")
  endif()
endfunction()
