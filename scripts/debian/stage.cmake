# SPDX-License-Identifier: GPL-3.0-or-later
# CPack pre-build script (CPACK_PRE_BUILD_SCRIPTS, scripts/package.cmake):
# what Debian policy asks of a binary package and a plain 'cmake --install'
# does not do, applied to the staging folder of every package after CPack
# has installed into it and before the .deb (and its md5sums) is made:
#   - manual pages compressed with gzip -9n (policy 12.1);
#   - /usr/share/doc/PACKAGE/copyright, machine-readable (policy 12.5);
#   - /usr/share/doc/PACKAGE/changelog.Debian.gz (policy 12.7).
# Runs in cpack, with the CPACK_* variables of CPackConfig.cmake.

find_program(SW_GZIP gzip REQUIRED)
if(NOT CPACK_PACKAGING_INSTALL_PREFIX)
  set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
endif()

function(sw_gzip file)   # FILE -> FILE.gz: no name, no time stamp (reproducible)
  execute_process(COMMAND ${SW_GZIP} -9nf ${file} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "stage.cmake: gzip ${file} failed (${rc})")
  endif()
  file(CHMOD ${file}.gz PERMISSIONS OWNER_READ OWNER_WRITE GROUP_READ WORLD_READ)
endfunction()

foreach(comp IN LISTS CPACK_COMPONENTS_ALL)
  set(root ${CPACK_TEMPORARY_DIRECTORY}/${comp})
  if(NOT IS_DIRECTORY ${root})
    continue()   # an empty component makes no package
  endif()
  string(TOUPPER ${comp} COMP)
  set(pkg ${CPACK_DEBIAN_${COMP}_PACKAGE_NAME})
  if(NOT pkg)
    message(FATAL_ERROR "stage.cmake: no CPACK_DEBIAN_${COMP}_PACKAGE_NAME")
  endif()
  set(usr ${root}${CPACK_PACKAGING_INSTALL_PREFIX})

  file(GLOB_RECURSE pages ${usr}/share/man/*)
  foreach(page IN LISTS pages)
    if(NOT page MATCHES "\\.gz$" AND NOT IS_SYMLINK ${page})
      sw_gzip(${page})
    endif()
  endforeach()

  set(doc ${usr}/share/doc/${pkg})
  file(MAKE_DIRECTORY ${doc})
  file(CHMOD ${doc} PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ GROUP_EXECUTE
                                WORLD_READ WORLD_EXECUTE)
  file(COPY_FILE ${CPACK_SW_DEB_COPYRIGHT} ${doc}/copyright)
  file(COPY_FILE ${CPACK_SW_DEB_CHANGELOG} ${doc}/changelog.Debian)
  sw_gzip(${doc}/changelog.Debian)
  file(CHMOD ${doc}/copyright PERMISSIONS OWNER_READ OWNER_WRITE GROUP_READ WORLD_READ)
endforeach()
