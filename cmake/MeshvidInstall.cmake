# install() of the libraries, their public headers and the exported CMake package:
#   find_package(meshvid) gives meshvid::decoder (with meshvid::common, meshvid::format),
#   meshvid::encoder (with meshvid::embree, when built) and meshvid::io (capture and mesh files,
#   when the tools are built); pkg-config gets meshvid.pc. Headers go under
#   <prefix>/include/meshvid/.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# The public headers of FOLDER (relative to the project root), less those that include a
# dependency the installed package does not promise (named in EXCLUDE).
function(meshvid_install_headers folder)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "" "EXCLUDE")
  file(GLOB headers RELATIVE ${PROJECT_SOURCE_DIR}/${folder} ${PROJECT_SOURCE_DIR}/${folder}/*.h)
  foreach(header ${headers})
    if(NOT header IN_LIST arg_EXCLUDE)
      install(FILES ${PROJECT_SOURCE_DIR}/${folder}/${header}
              DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/meshvid/${folder})
    endif()
  endforeach()
endfunction()

function(meshvid_install_package)
  set(targets meshvid_format meshvid_common meshvid_decoder)
  # Libraries and -l flags for meshvid.pc, most dependent first, and the pkg-config modules and
  # plain libraries they need. meshvid's libraries are static, so whoever links them links
  # their dependencies too: these go in Requires and Libs, not in the .private fields (which
  # `pkg-config --static` would expand into the dependencies' own static dependencies).
  set(pc_libs "-lmeshvid_decoder -lmeshvid_common -lmeshvid_format")
  set(pc_requires "libavcodec libavutil libzstd draco")
  set(pc_libs_extra "")
  meshvid_install_headers(format)
  # point_tree.h: nanoflann, for the encoder and eval; embree_scene.h: with the encoder.
  meshvid_install_headers(codec/common EXCLUDE point_tree.h embree_scene.h)
  meshvid_install_headers(codec/dec EXCLUDE ffmpeg_util.h)     # libavcodec: internal
  if(MESHVID_BUILD_ENCODER)
    list(APPEND targets meshvid_embree meshvid_encoder)
    set(pc_libs "-lmeshvid_encoder -lmeshvid_embree ${pc_libs}")
    install(FILES ${PROJECT_SOURCE_DIR}/codec/common/embree_scene.h
            DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/meshvid/codec/common)
    string(APPEND pc_requires " tbb openmesh")
    string(APPEND pc_libs_extra " -lembree3")
    # The encoder's public API: its root (encoder.h, options.h, summary.h, frame_source.h); the
    # stages' folders are internal.
    meshvid_install_headers(codec/enc)
  endif()
  if(MESHVID_BUILD_TOOLS)
    list(APPEND targets meshvid_io)
    set(pc_libs "-lmeshvid_io ${pc_libs}")
    string(APPEND pc_requires " libpng")
    meshvid_install_headers(tools/io EXCLUDE mesh_io_internal.h)
  endif()
  install(FILES ${PROJECT_BINARY_DIR}/include/meshvid/version.h
          DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/meshvid)

  install(TARGETS ${targets} EXPORT meshvidTargets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
          RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  set(config_dir ${CMAKE_INSTALL_LIBDIR}/cmake/meshvid)
  install(EXPORT meshvidTargets NAMESPACE meshvid:: DESTINATION ${config_dir})
  set(MESHVID_PACKAGE_HAS_ENCODER ${MESHVID_BUILD_ENCODER})
  set(MESHVID_PACKAGE_HAS_IO ${MESHVID_BUILD_TOOLS})
  configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/meshvidConfig.cmake.in
                                ${PROJECT_BINARY_DIR}/meshvidConfig.cmake
                                INSTALL_DESTINATION ${config_dir})
  # 0.x: a minor version may break the API.
  write_basic_package_version_file(${PROJECT_BINARY_DIR}/meshvidConfigVersion.cmake
                                   COMPATIBILITY SameMinorVersion)
  install(FILES ${PROJECT_BINARY_DIR}/meshvidConfig.cmake
                ${PROJECT_BINARY_DIR}/meshvidConfigVersion.cmake
          DESTINATION ${config_dir})

  # Relocatable: the prefix is found from where meshvid.pc lies (<prefix>/<libdir>/pkgconfig).
  file(RELATIVE_PATH pc_to_prefix /prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig /prefix)
  set(MESHVID_PC_PREFIX "\${pcfiledir}/${pc_to_prefix}")
  set(MESHVID_PC_LIBS ${pc_libs})
  set(MESHVID_PC_REQUIRES ${pc_requires})
  set(MESHVID_PC_LIBS_EXTRA ${pc_libs_extra})
  configure_file(${PROJECT_SOURCE_DIR}/cmake/meshvid.pc.in ${PROJECT_BINARY_DIR}/meshvid.pc @ONLY)
  install(FILES ${PROJECT_BINARY_DIR}/meshvid.pc
          DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
endfunction()
