# Every dependency comes from Debian 12 packages installed by scripts/bootstrap.
find_package(Threads REQUIRED)
find_package(fmt REQUIRED)
find_package(nlohmann_json 3.10 REQUIRED)
find_package(CLI11 CONFIG QUIET)
if(NOT TARGET CLI11::CLI11)
  # Debian's libcli11-dev is header-only; its CMake package may be absent.
  add_library(CLI11::CLI11 INTERFACE IMPORTED)
endif()
find_package(GTest REQUIRED)
find_package(benchmark REQUIRED)

# OpenImageIO 2.4 (Debian 12): the CMake package's imported target lists /usr/include/opencv4 in
# INTERFACE_INCLUDE_DIRECTORIES, which does not exist unless libopencv-dev is installed, and
# generation then fails. Use pkg-config (OpenImageIO.pc) instead and build our own imported target.
find_package(PkgConfig REQUIRED)
pkg_check_modules(OIIO REQUIRED IMPORTED_TARGET OpenImageIO)
add_library(tfu_oiio INTERFACE)
target_link_libraries(tfu_oiio INTERFACE PkgConfig::OIIO)

# libzip (Debian libzip-dev): reads the .pk3 (zip) archives of Quake III / OpenArena game data
# (cmodel/pk3.cpp). Through pkg-config (libzip.pc), like OpenImageIO.
pkg_check_modules(LIBZIP REQUIRED IMPORTED_TARGET libzip)

# Block-compressed texture encoders (cmodel/block_encode.cpp), also the outside references of the
# decoder tests: ARM's libastcenc 4.2 (Debian libastcenc-dev, a CMake package that accepts 4.2.x
# only; its imported target brings ASTCENC_DYNAMIC_LIBRARY) and libsquish 1.15 (libsquish-dev,
# whose libsquish.pc has an empty prefix, so header and library are found directly).
find_package(astcenc 4.2 CONFIG REQUIRED)
find_path(SQUISH_INCLUDE_DIR squish.h REQUIRED)
find_library(SQUISH_LIBRARY squish REQUIRED)
