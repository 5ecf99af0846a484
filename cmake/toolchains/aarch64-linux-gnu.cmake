# Cross build for arm64 module boards with Debian's cross toolchain (docs/install.md, "arm64"):
#   cmake -S . -B build-arm64 --toolchain cmake/toolchains/aarch64-linux-gnu.cmake \
#         -DAHHS_MODULE_ONLY=ON -DAHHS_ARM64_LCM=DIR
# Needs crossbuild-essential-arm64 and the arm64 development packages of GLib and toml++
# (multiarch); tools/cross-arm64 installs them. LCM's Debian packages are not multiarch
# co-installable (installing liblcm-dev:arm64 removes the amd64 one), so their arm64 files are
# unpacked into DIR instead (AHHS_ARM64_LCM; tools/cross-arm64 makes it).
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)
set(AHHS_DEB_ARCHITECTURE arm64)
# x86-64 has no fused multiply-add in its baseline, so the native build never contracts a*b+c;
# arm64 has one, and GCC would use it in C++. Off, so the controller's arithmetic is the same to
# the bit on both (the test compares fitnesses).
set(CMAKE_C_FLAGS_INIT "-ffp-contract=off")
set(CMAKE_CXX_FLAGS_INIT "-ffp-contract=off")

set(CMAKE_FIND_ROOT_PATH /usr/aarch64-linux-gnu)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)  # lcm-gen, help2man: the build machine's
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY BOTH)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE BOTH)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE BOTH)  # header-only Eigen, CLI11, nlohmann-json

# pkg-config: the arm64 multiarch .pc files, and LCM's from its unpacked directory.
set(AHHS_ARM64_LCM "" CACHE PATH "the arm64 files of liblcm1 and liblcm-dev, unpacked (tools/cross-arm64)")
# (CMake reads this file again for its compiler checks, without the cache: keep the first setting.)
if(AHHS_ARM64_LCM)
  set(ENV{PKG_CONFIG_LIBDIR}
      "${AHHS_ARM64_LCM}/usr/lib/aarch64-linux-gnu/pkgconfig:/usr/lib/aarch64-linux-gnu/pkgconfig:/usr/share/pkgconfig")
endif()
