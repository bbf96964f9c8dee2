# SPDX-License-Identifier: GPL-3.0-or-later
# CPack pre-build script (CPACK_PRE_BUILD_SCRIPTS, scripts/package.cmake):
# the source tarball ('cmake --build build --target package_source') gets a
# file COMMIT at its top with the commit it was made from, which a build
# from the tarball, having no git, reports as its commit
# (scripts/commit.cmake).  Binary packages are left alone.
if(NOT CPACK_INSTALLED_DIRECTORIES)
  return()   # a binary package: installed by the project, not copied from the source
endif()
find_package(Git QUIET)
if(NOT GIT_FOUND)
  message(WARNING "release-commit.cmake: git not found: the source package has no COMMIT")
  return()
endif()
execute_process(COMMAND ${GIT_EXECUTABLE} -C ${CPACK_SW_SOURCE_DIR} rev-parse HEAD
                OUTPUT_VARIABLE commit OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE rc
                ERROR_QUIET)
execute_process(COMMAND ${GIT_EXECUTABLE} -C ${CPACK_SW_SOURCE_DIR} status --porcelain
                        --untracked-files=no
                OUTPUT_VARIABLE changes RESULT_VARIABLE rc2 ERROR_QUIET)
if(NOT rc EQUAL 0 OR NOT commit MATCHES "^[0-9a-f]+$")
  message(WARNING "release-commit.cmake: not a git checkout: the source package has no COMMIT")
  return()
endif()
if(NOT rc2 EQUAL 0 OR NOT changes STREQUAL "")
  # the files packed are not that commit's: no commit is better than a wrong one
  message(WARNING "release-commit.cmake: the checkout has changes: the source package has no "
                  "COMMIT; commit them first")
  return()
endif()
file(WRITE ${CPACK_TEMPORARY_DIRECTORY}/COMMIT "${commit}\n")
