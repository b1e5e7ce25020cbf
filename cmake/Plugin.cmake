# The ParaView plugin, declared by the top-level paraview.plugin. paraview_plugin_build adds the
# descriptor's folder (the repository's top) as a subdirectory, and the top-level CMakeLists.txt
# sends that second entry here. Two callers:
#  - this project's own build (CMakeLists.txt), which has already built the filters' VTK module
#    with its Python wrapping and the plugin's server-manager helpers (Plugin/ServerManager): the
#    plugin only adds the server-manager XML and their client-server wrapping;
#  - a ParaView build given this repository in PARAVIEW_EXTERNAL_PLUGIN_DIRS: nothing of ours is
#    built yet, so the kernels and both modules are built here, inside the plugin.
set(tsynth_plugin_xmls
  Plugin/TerrainReader.xml
  Plugin/TerrainSketchReader.xml
  Plugin/TerrainHillshade.xml
  Plugin/TerrainFeatureExtractor.xml
  Plugin/TerrainSketchFeatures.xml
  Plugin/TerrainSketchLines.xml
  Plugin/TerrainCandidateBuilder.xml
  Plugin/TerrainPatchMatcher.xml
  Plugin/TerrainPatchExtractor.xml
  Plugin/TerrainGraphCutMerger.xml
  Plugin/TerrainPoissonSolver.xml
  Plugin/TerrainPitRemoval.xml
  Plugin/TerrainOptimisation.xml
  Plugin/TerrainDistanceSynthesis.xml
  Plugin/TerrainSynthesis.xml
  Plugin/TerrainTileWriter.xml
  Plugin/TerrainLineWidths.xml)

# Colour maps and the DEM reader ParaView uses once the plugin is loaded.
set(tsynth_plugin_sources "${CMAKE_CURRENT_LIST_DIR}/../Plugin/TerrainSynthesisDefaults.cxx")

if (TARGET TerrainSynthesis::Filters)
  paraview_add_plugin(TerrainSynthesis
    VERSION "${TSYNTH_VERSION}"
    MODULES TerrainSynthesis::Filters TerrainSynthesis::ServerManager
    SOURCES ${tsynth_plugin_sources}
    SERVER_MANAGER_XML ${tsynth_plugin_xmls})
  target_link_libraries(TerrainSynthesis PRIVATE ParaView::RemotingServerManager)
else ()
  message(STATUS "TerrainSynthesis ${TSYNTH_VERSION}: built as an external plugin of this ParaView")
  set(CMAKE_CXX_STANDARD 17)
  set(CMAKE_CXX_STANDARD_REQUIRED ON)
  set(CMAKE_CXX_EXTENSIONS OFF)
  include(GNUInstallDirs)
  include("${CMAKE_CURRENT_LIST_DIR}/Dependencies.cmake")
  add_subdirectory("${CMAKE_CURRENT_LIST_DIR}/../Kernels" "${CMAKE_CURRENT_BINARY_DIR}/Kernels")
  paraview_add_plugin(TerrainSynthesis
    VERSION "${TSYNTH_VERSION}"
    MODULES TerrainSynthesis::Filters TerrainSynthesis::ServerManager
    MODULE_FILES "${CMAKE_CURRENT_LIST_DIR}/../Filters/vtk.module"
      "${CMAKE_CURRENT_LIST_DIR}/../Plugin/ServerManager/vtk.module"
    SOURCES ${tsynth_plugin_sources}
    SERVER_MANAGER_XML ${tsynth_plugin_xmls})
  target_link_libraries(TerrainSynthesis PRIVATE ParaView::RemotingServerManager)
endif ()
