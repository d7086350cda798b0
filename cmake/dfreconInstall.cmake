# What `cmake --install build --prefix P` puts under P (docs/building.md):
#   bin/dfrecon
#   lib/libdfrecon_FOLDER.a            one static library per stage folder
#   lib/libdfrecon_api.a, include/dfrecon/*.hpp   the public API
#   lib/python3.X/site-packages/dfrecon  the Python module (python/CMakeLists.txt)
#   include/dfrecon/FOLDER/*.hpp       the stage headers the public API needs
#                                      (those include/dfrecon/*.hpp include, and
#                                      theirs, kernels/*.cl text among them),
#                                      nothing else of the stages' internals
#   lib/cmake/dfrecon/                 the package: dfreconConfig.cmake,
#                                      dfreconConfigVersion.cmake, the
#                                      dfrecon:: targets, their dependencies
#   share/man/man1/dfrecon.1           man page, from the program's --help
#   share/bash-completion/completions/dfrecon
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(DFRECON_LIBRARY_FOLDERS kernels cl geometry contours io field shapes recon neighbours simplify sdm segment compare algebra)
set(dfrecon_libraries "")
foreach(folder IN LISTS DFRECON_LIBRARY_FOLDERS)
  # dfrecon_recon is dfrecon::recon to package users, and to projects that
  # add this tree as a subdirectory.
  set_target_properties(dfrecon_${folder} PROPERTIES EXPORT_NAME ${folder})
  add_library(dfrecon::${folder} ALIAS dfrecon_${folder})
  list(APPEND dfrecon_libraries dfrecon_${folder})
endforeach()

# The files the public headers need: every project file they include, and
# those include, by following the #include "..." lines from
# include/dfrecon/*.hpp (a line inside #if counts too: the walk may take a
# header more, never one less). Configured again when any of them changes.
function(dfrecon_public_header_closure out)
  file(GLOB pending RELATIVE ${PROJECT_SOURCE_DIR} ${PROJECT_SOURCE_DIR}/include/dfrecon/*.hpp)
  set(found "")
  while(pending)
    list(POP_FRONT pending file)
    if(file IN_LIST found)
      continue()
    endif()
    list(APPEND found ${file})
    set_property(DIRECTORY ${PROJECT_SOURCE_DIR} APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS
                 ${PROJECT_SOURCE_DIR}/${file})
    file(STRINGS ${PROJECT_SOURCE_DIR}/${file} lines REGEX "^[ \t]*#[ \t]*include[ \t]*\"")
    foreach(line IN LISTS lines)
      string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*\"([^\"]+)\".*" "\\1" included "${line}")
      if(EXISTS ${PROJECT_SOURCE_DIR}/${included})
        list(APPEND pending ${included})
      elseif(EXISTS ${PROJECT_SOURCE_DIR}/include/${included})
        list(APPEND pending include/${included})
      endif()
    endforeach()
  endwhile()
  set(${out} ${found} PARENT_SCOPE)
endfunction()

dfrecon_public_header_closure(dfrecon_public_files)
foreach(file IN LISTS dfrecon_public_files)
  get_filename_component(folder ${file} DIRECTORY)
  if(folder STREQUAL "include/dfrecon")
    continue()  # installed whole below
  endif()
  install(FILES ${PROJECT_SOURCE_DIR}/${file}
          DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/dfrecon/${folder})
endforeach()

# The public API: its library, and its headers straight under include/dfrecon/.
set_target_properties(dfrecon_api PROPERTIES EXPORT_NAME api)
add_library(dfrecon::api ALIAS dfrecon_api)
list(APPEND dfrecon_libraries dfrecon_api)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/dfrecon/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/dfrecon
        FILES_MATCHING PATTERN "*.hpp")

install(TARGETS dfrecon RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS ${dfrecon_libraries} EXPORT dfreconTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})

set(dfrecon_package_dir ${CMAKE_INSTALL_LIBDIR}/cmake/dfrecon)
install(EXPORT dfreconTargets NAMESPACE dfrecon:: DESTINATION ${dfrecon_package_dir})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/dfreconConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/dfreconConfig.cmake
                              INSTALL_DESTINATION ${dfrecon_package_dir})
# Before 1.0 a minor version may change the interface.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/dfreconConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/dfreconConfig.cmake
              ${PROJECT_BINARY_DIR}/dfreconConfigVersion.cmake
              ${PROJECT_SOURCE_DIR}/cmake/dfreconDependencies.cmake
        DESTINATION ${dfrecon_package_dir})

# The man page and the bash completion are made from the built program's
# --help, so they never disagree with it (scripts/help_pages.py).
find_package(Python3 REQUIRED COMPONENTS Interpreter)
set(DFRECON_MAN_PAGE ${PROJECT_BINARY_DIR}/share/man/man1/dfrecon.1)
set(DFRECON_COMPLETION ${PROJECT_BINARY_DIR}/share/bash-completion/completions/dfrecon)
add_custom_command(
  OUTPUT ${DFRECON_MAN_PAGE} ${DFRECON_COMPLETION}
  # The sanitizer build's program checks for leaks at exit; --help has none to
  # find, and a build step is no place for LeakSanitizer's ptrace tracer.
  COMMAND ${CMAKE_COMMAND} -E env ASAN_OPTIONS=detect_leaks=0
          ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/scripts/help_pages.py $<TARGET_FILE:dfrecon>
          --version ${PROJECT_VERSION} --man ${DFRECON_MAN_PAGE} --completion ${DFRECON_COMPLETION}
  DEPENDS dfrecon ${PROJECT_SOURCE_DIR}/scripts/help_pages.py
          ${PROJECT_SOURCE_DIR}/scripts/dfrecon_help.py ${PROJECT_SOURCE_DIR}/scripts/man_page.py
          ${PROJECT_SOURCE_DIR}/scripts/bash_completion.py
  COMMENT "Man page and bash completion from dfrecon --help"
  VERBATIM)
add_custom_target(dfrecon_help_pages ALL DEPENDS ${DFRECON_MAN_PAGE} ${DFRECON_COMPLETION})
install(FILES ${DFRECON_MAN_PAGE} DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
install(FILES ${DFRECON_COMPLETION}
        DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions)
