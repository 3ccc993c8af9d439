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

file(GLOB fetic_docs "${PROJECT_SOURCE_DIR}/docs/*.md")
install(FILES ${PROJECT_SOURCE_DIR}/README.md ${fetic_docs} DESTINATION ${CMAKE_INSTALL_DOCDIR})

# Debian package. dpkg-shlibdeps derives the library dependencies from the binary; the
# Mesa drivers are loaded at run time (EGL, software rendering), so they are named here.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME fetic)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "frictionless contact of elastic struts solved by FETI and FETI-C")
string(CONCAT CPACK_PACKAGE_DESCRIPTION
    "fetic solves the frictionless contact of elastic struts (bar, plane stress) by dual "
    "domain decomposition, writes result files (JSON, CSV, ParaView .vtu) and renders "
    "frames, movies and the thesis' figures without a display.")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "fetic developers <fetic@localhost>")
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "libegl-mesa0, libgl1-mesa-dri")
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "ffmpeg")
set(CPACK_STRIP_FILES ON)
include(CPack)
