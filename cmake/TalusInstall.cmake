# What `cmake --install` and `cpack -G DEB` deliver (docs/install.md), and the QGIS plugin zip
# that QGIS's "Install from ZIP" takes. Included by the top-level CMakeLists.txt after the
# program's target exists.
include(GNUInstallDirs)

install(TARGETS talus RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

# The QGIS Processing provider: its folder, and the same folder as a zip, under share/talus/qgis.
# metadata.txt states the plugin's version; it must be the program's.
set(plugin_folder ${PROJECT_SOURCE_DIR}/gis/qgis/talus_processing)
file(STRINGS ${plugin_folder}/metadata.txt plugin_version REGEX "^version=")
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${plugin_folder}/metadata.txt)
if(NOT plugin_version STREQUAL "version=${PROJECT_VERSION}")
  message(FATAL_ERROR "gis/qgis/talus_processing/metadata.txt says ${plugin_version}; the project is ${PROJECT_VERSION}")
endif()
file(GLOB plugin_files CONFIGURE_DEPENDS RELATIVE ${PROJECT_SOURCE_DIR}/gis/qgis
     ${plugin_folder}/*.py ${plugin_folder}/metadata.txt)
list(SORT plugin_files)
set(plugin_zip ${PROJECT_BINARY_DIR}/talus-qgis-plugin.zip)
list(TRANSFORM plugin_files PREPEND ${PROJECT_SOURCE_DIR}/gis/qgis/ OUTPUT_VARIABLE plugin_sources)
# One folder, talus_processing/, at the zip's root with metadata.txt in it, as QGIS expects; a
# fixed time stamp on every entry, so the same sources give the same zip.
add_custom_command(
  OUTPUT ${plugin_zip}
  COMMAND ${CMAKE_COMMAND} -E tar cf ${plugin_zip} --format=zip "--mtime=2000-01-01 00:00:00 UTC" -- ${plugin_files}
  WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}/gis/qgis
  DEPENDS ${plugin_sources}
  COMMENT "Packing the QGIS plugin: talus-qgis-plugin.zip"
  VERBATIM)
add_custom_target(talus_qgis_plugin_zip ALL DEPENDS ${plugin_zip})
install(FILES ${plugin_sources} DESTINATION ${CMAKE_INSTALL_DATADIR}/talus/qgis/talus_processing)
install(FILES ${plugin_zip} DESTINATION ${CMAKE_INSTALL_DATADIR}/talus/qgis)

# The sample scene with its example study (`talus study .../study.toml --out DIR`).
install(FILES sample_dem/dem.tif sample_dem/lithology.tif sample_dem/vegetation.tif sample_dem/rockfall_release.gpkg
              sample_dem/mudflow_release.gpkg sample_dem/study.toml sample_dem/README.md
        DESTINATION ${CMAKE_INSTALL_DATADIR}/talus/examples/sample_dem)

# The user's guide: README.md beside docs/, so that the README's links hold.
install(FILES README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY docs DESTINATION ${CMAKE_INSTALL_DOCDIR})

# cpack -G DEB: dpkg-shlibdeps finds the shared libraries the program links, so the package
# depends on runtime libraries only; QGIS (projects, quicklooks, the plugin) and OpenMPI
# (mpirun) are recommended and suggested.
set(CPACK_PACKAGE_NAME talus)
set(CPACK_PACKAGE_VENDOR "The Talus developers")
set(CPACK_PACKAGE_CONTACT "The Talus developers <talus@invalid>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${PROJECT_DESCRIPTION}")
set(CPACK_PACKAGE_DESCRIPTION
    "Talus reads a georeferenced DEM with lithology and vegetation maps, runs stochastic rock-fall
trajectories and smoothed-particle mud flows on the bilinear ground model of Gascuel et al.
(1998), and writes Cloud Optimized GeoTIFF hazard layers that open styled in QGIS.")
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "python3-qgis")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "qgis, openmpi-bin")
include(CPack)
