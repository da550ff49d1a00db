# Every third-party dependency of meshvid, found once here. All are Debian packages
# installed by scripts/setup; the package names are listed beside each.
find_package(Threads REQUIRED)
find_package(PkgConfig REQUIRED)
find_package(Eigen3 3.3 REQUIRED NO_MODULE)          # libeigen3-dev
find_package(TBB REQUIRED)                           # libtbb-dev
find_package(embree 3 REQUIRED)                      # libembree-dev
find_package(nlohmann_json 3 REQUIRED)               # nlohmann-json3-dev
find_package(CLI11 REQUIRED)                         # libcli11-dev
find_package(nanoflann REQUIRED)                     # libnanoflann-dev
find_package(PNG REQUIRED)                           # libpng-dev (16-bit depth images)
pkg_check_modules(ZSTD REQUIRED IMPORTED_TARGET libzstd)                      # libzstd-dev
pkg_check_modules(FFMPEG REQUIRED IMPORTED_TARGET libavcodec libavformat libavutil)  # libav*-dev
find_package(draco REQUIRED)                         # libdraco-dev: draco::draco
find_package(OpenMesh REQUIRED CONFIG)               # libopenmesh-dev: OpenMeshCore, OpenMeshTools

if(MESHVID_BUILD_TESTS)
  find_package(GTest REQUIRED)                       # libgtest-dev
endif()
if(MESHVID_BUILD_BENCH)
  find_package(benchmark REQUIRED)                   # libbenchmark-dev
endif()
