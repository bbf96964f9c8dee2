# SPDX-License-Identifier: GPL-3.0-or-later
# The 'uninstall' target (scripts/package.cmake): removes what the last
# 'cmake --install' from this build folder installed, as listed in its
# install_manifest.txt, then the folders of swaywatch's own that are left
# empty (share/swaywatch, share/doc/swaywatch, include/swaywatch ...; shared
# folders such as share/man/man1 stay), then refreshes the linker's cache.
#   cmake --build build --target uninstall      (sudo for a system prefix)
# Needs SW_MANIFEST.

include(${CMAKE_CURRENT_LIST_DIR}/ldconfig.cmake)

if(NOT EXISTS "${SW_MANIFEST}")
  message(FATAL_ERROR "No ${SW_MANIFEST}: nothing was installed from this build folder "
                      "(or it was removed already)")
endif()
file(STRINGS "${SW_MANIFEST}" files)
set(dirs "")
set(libdir "")
set(failed 0)
foreach(f IN LISTS files)
  if(EXISTS "${f}" OR IS_SYMLINK "${f}")
    message(STATUS "Removing: ${f}")
    file(REMOVE "${f}")
    if(EXISTS "${f}" OR IS_SYMLINK "${f}")
      message(SEND_ERROR "Could not remove ${f} (root needed?)")
      set(failed 1)
    endif()
  else()
    message(STATUS "Not there: ${f}")
  endif()
  get_filename_component(d "${f}" DIRECTORY)
  if(f MATCHES "/libswaywatch\\.so\\.0$")
    set(libdir "${d}")
  endif()
  # Every folder above the file whose name is swaywatch's own.
  while(d MATCHES "/(swaywatch|swaywatch-[^/]*|libswaywatch-dev)(/|$)")
    list(APPEND dirs "${d}")
    get_filename_component(d "${d}" DIRECTORY)
  endwhile()
endforeach()
# Deepest first; rmdir leaves a folder that is not empty alone.
list(REMOVE_DUPLICATES dirs)
list(SORT dirs ORDER DESCENDING)
foreach(d IN LISTS dirs)
  if(IS_DIRECTORY "${d}")
    execute_process(COMMAND rmdir "${d}" RESULT_VARIABLE rc ERROR_QUIET)
    if(rc EQUAL 0)
      message(STATUS "Removing folder: ${d}")
    endif()
  endif()
endforeach()
if(failed)
  message(FATAL_ERROR "Some files could not be removed")
endif()
if(libdir)
  sw_ldconfig("${libdir}" uninstall)
endif()
