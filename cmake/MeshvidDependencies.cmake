# Every third-party dependency of meshvid, found for the targets being built only: a
# decoder-only configure (MESHVID_BUILD_ENCODER=OFF, MESHVID_BUILD_TOOLS=OFF,
# MESHVID_BUILD_TESTS=OFF) needs nothing from the later sections. All are Debian packages
# installed by scripts/setup; the package names are listed beside each. The installed package's
# meshvidConfig.cmake (cmake/meshvidConfig.cmake.in) finds the same ones again.
find_package(PkgConfig REQUIRED)

# format/ needs nothing. meshvid_common and meshvid_decoder (codec/common, codec/dec):
find_package(Eigen3 3.3 REQUIRED NO_MODULE)          # libeigen3-dev
pkg_check_modules(ZSTD REQUIRED IMPORTED_TARGET libzstd)                # libzstd-dev
pkg_check_modules(FFMPEG REQUIRED IMPORTED_TARGET libavcodec libavutil) # libavcodec/libavutil-dev
find_package(draco REQUIRED)                         # libdraco-dev: draco::draco

# meshvid_encoder (codec/enc):
if(MESHVID_BUILD_ENCODER)
  find_package(TBB REQUIRED)                         # libtbb-dev
  find_package(embree 3 REQUIRED)                    # libembree-dev
  find_package(nanoflann REQUIRED)                   # libnanoflann-dev
  find_package(OpenMesh REQUIRED CONFIG)             # libopenmesh-dev: OpenMeshCore, OpenMeshTools
endif()

# The tool libraries (tools/io, sim, eval, export, render, bench) and the meshvid executable:
if(MESHVID_BUILD_TOOLS)
  find_package(nlohmann_json 3 REQUIRED)             # nlohmann-json3-dev
  find_package(CLI11 REQUIRED)                       # libcli11-dev
  find_package(PNG REQUIRED)                         # libpng-dev (16-bit depth images, pictures)
  pkg_check_modules(AVFORMAT REQUIRED IMPORTED_TARGET libavformat)  # libavformat-dev (MP4)
endif()

if(MESHVID_BUILD_TESTS)
  find_package(GTest REQUIRED)                       # libgtest-dev
endif()
if(MESHVID_BUILD_BENCH)
  find_package(benchmark REQUIRED)                   # libbenchmark-dev
endif()
