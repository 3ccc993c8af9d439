# Installing fetic and packaging it for Debian (docs/INSTALL.md).
#   cmake --install build --prefix P   P/bin/fetic, P/share/fetic/{scenes,fonts}, P/share/doc/fetic
#   cpack --config build/CPackConfig.cmake -G DEB   fetic_<version>_<arch>.deb (prefix /usr)
# fetic finds its data from the executable's place (app/data_paths.hpp), so the installed
# tree can be moved as a whole.
include(GNUInstallDirs)

install(TARGETS fetic RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
file(GLOB fetic_bundled_scenes "${PROJECT_SOURCE_DIR}/scenes/*.toml")
install(FILES ${fetic_bundled_scenes} DESTINATION ${CMAKE_INSTALL_DATADIR}/fetic/scenes)

# The fonts of rendered text travel with fetic: a copy of fonts-dejavu-core's two files
# and their licence, so rendering works in any installed tree.
set(fetic_dejavu_dir /usr/share/fonts/truetype/dejavu)
if(EXISTS ${fetic_dejavu_dir}/DejaVuSans.ttf AND EXISTS ${fetic_dejavu_dir}/DejaVuSans-Bold.ttf)
  install(FILES ${fetic_dejavu_dir}/DejaVuSans.ttf ${fetic_dejavu_dir}/DejaVuSans-Bold.ttf
          DESTINATION ${CMAKE_INSTALL_DATADIR}/fetic/fonts)
  if(EXISTS /usr/share/doc/fonts-dejavu-core/copyright)
    install(FILES /usr/share/doc/fonts-dejavu-core/copyright
            DESTINATION ${CMAKE_INSTALL_DATADIR}/fetic/fonts RENAME DejaVu-LICENSE)
  endif()
else()
  message(WARNING "DejaVu fonts not found (apt-get install fonts-dejavu-core): the installed "
                  "fetic renders text with ImGui's built-in font")
endif()

# The documentation keeps the source tree's layout, so README.md's links into docs/
# (pages and pictures) and the pages' links to each other work where it is installed.
file(GLOB fetic_docs "${PROJECT_SOURCE_DIR}/docs/*.md" "${PROJECT_SOURCE_DIR}/docs/*.png")
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(FILES ${fetic_docs} DESTINATION ${CMAKE_INSTALL_DOCDIR}/docs)
install(FILES ${PROJECT_SOURCE_DIR}/packaging/copyright DESTINATION ${CMAKE_INSTALL_DOCDIR})
# The helper script the README names for pictures of the ParaView files.
install(PROGRAMS ${PROJECT_SOURCE_DIR}/scripts/vtu_picture.py
        DESTINATION ${CMAKE_INSTALL_DATADIR}/fetic/scripts)

# The man page, generated from the help texts of the program just built (every command's
# options, exit statuses and units), compressed as Debian wants it.
add_custom_command(
  OUTPUT ${PROJECT_BINARY_DIR}/fetic.1.gz
  COMMAND ${CMAKE_COMMAND} -DFETIC=$<TARGET_FILE:fetic> -DOUT=${PROJECT_BINARY_DIR}/fetic.1
          -DVERSION=${PROJECT_VERSION} -P ${PROJECT_SOURCE_DIR}/packaging/make_man_page.cmake
  COMMAND gzip -9nf ${PROJECT_BINARY_DIR}/fetic.1
  DEPENDS fetic ${PROJECT_SOURCE_DIR}/packaging/make_man_page.cmake
  COMMENT "Writing the man page from fetic's help texts")
add_custom_target(fetic_man_page ALL DEPENDS ${PROJECT_BINARY_DIR}/fetic.1.gz)
install(FILES ${PROJECT_BINARY_DIR}/fetic.1.gz DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)

# Debian's changelog (lintian requires one), from the project version.
string(TIMESTAMP fetic_changelog_date "%a, %d %b %Y %H:%M:%S +0000" UTC)
file(WRITE ${PROJECT_BINARY_DIR}/changelog.Debian
     "fetic (${PROJECT_VERSION}) unstable; urgency=medium\n\n"
     "  * Package built from the fetic source tree (see README.md).\n\n"
     " -- fetic developers <fetic@example.org>  ${fetic_changelog_date}\n")
add_custom_command(
  OUTPUT ${PROJECT_BINARY_DIR}/changelog.Debian.gz
  COMMAND gzip -9nkf ${PROJECT_BINARY_DIR}/changelog.Debian
  DEPENDS ${PROJECT_BINARY_DIR}/changelog.Debian)
add_custom_target(fetic_changelog ALL DEPENDS ${PROJECT_BINARY_DIR}/changelog.Debian.gz)
install(FILES ${PROJECT_BINARY_DIR}/changelog.Debian.gz DESTINATION ${CMAKE_INSTALL_DOCDIR})

# Debian package. dpkg-shlibdeps derives the library dependencies from the binary; the
# Mesa drivers are loaded at run time (EGL, software rendering), so they are named here.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME fetic)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "frictionless contact of elastic struts solved by FETI and FETI-C")
string(CONCAT CPACK_PACKAGE_DESCRIPTION
    "fetic solves the frictionless contact of elastic struts - bars, plane-stress "
    "struts and frames of beams with pinned and rigid joints - by dual domain "
    "decomposition (FETI, FETI-C, MPRGP) and the primal active-set method, in one "
    "process or under mpirun, writes result files (JSON, CSV, ParaView .vtu) and "
    "renders frames, movies and the thesis' figures without a display; fetic gui "
    "shows a solve live in a window.")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "fetic developers <fetic@example.org>")
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# python3: the installed helper script vtu_picture.py is a python3 program (lintian)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "libegl-mesa0, libgl1-mesa-dri, python3")
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "ffmpeg")
set(CPACK_STRIP_FILES ON)
include(CPack)
