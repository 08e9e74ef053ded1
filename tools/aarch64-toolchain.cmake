# CMake toolchain file for the aarch64 (arm64) cross build, used by tools/cross_aarch64.sh:
#
#   cmake -S . -B build-aarch64 -DCMAKE_TOOLCHAIN_FILE=tools/aarch64-toolchain.cmake \
#         -DSYSROOT=<absolute path of the arm64 sysroot> ...
#
# Compilers: Debian's gcc/g++-aarch64-linux-gnu, which bring their own C library and libstdc++ in
# /usr/aarch64-linux-gnu. SYSROOT holds the arm64 -dev packages (OpenEXR, Imath, zlib, FFTW and
# the header-only libraries) unpacked from Debian's .debs; libraries, headers, CMake packages and
# pkg-config files are looked up only there and in /usr/aarch64-linux-gnu, programs only on the
# host. SYSROOT is not passed to the compiler as --sysroot (its C library is the toolchain's).
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)

# SYSROOT from the command line, else from the environment (try_compile projects re-read this
# file with only the variables listed in CMAKE_TRY_COMPILE_PLATFORM_VARIABLES).
if(DEFINED SYSROOT AND NOT SYSROOT STREQUAL "")
  set(ENV{OCEANREF_AARCH64_SYSROOT} "${SYSROOT}")
elseif(DEFINED ENV{OCEANREF_AARCH64_SYSROOT})
  set(SYSROOT "$ENV{OCEANREF_AARCH64_SYSROOT}")
else()
  message(FATAL_ERROR "aarch64-toolchain.cmake: pass -DSYSROOT=<arm64 sysroot> "
                      "(tools/cross_aarch64.sh creates it in build/_deps/aarch64-sysroot)")
endif()
if(NOT IS_DIRECTORY "${SYSROOT}/usr/include")
  message(FATAL_ERROR "aarch64-toolchain.cmake: ${SYSROOT} is not an arm64 sysroot")
endif()
set(SYSROOT "${SYSROOT}" CACHE PATH "arm64 sysroot of the cross build's libraries")
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES SYSROOT)

set(OCEANREF_CROSS_PREFIX aarch64-linux-gnu)
set(CMAKE_C_COMPILER ${OCEANREF_CROSS_PREFIX}-gcc)
set(CMAKE_CXX_COMPILER ${OCEANREF_CROSS_PREFIX}-g++)
set(CMAKE_LIBRARY_ARCHITECTURE ${OCEANREF_CROSS_PREFIX})

set(CMAKE_FIND_ROOT_PATH "${SYSROOT}" /usr/${OCEANREF_CROSS_PREFIX})
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

# The shared libraries' own dependencies (libOpenEXR -> libImath, libz, ...) are resolved by the
# linker in the sysroot, never on the host.
set(_oceanref_rpath_link
    "-Wl,-rpath-link,${SYSROOT}/usr/lib/${OCEANREF_CROSS_PREFIX}:${SYSROOT}/lib/${OCEANREF_CROSS_PREFIX}")
set(CMAKE_EXE_LINKER_FLAGS_INIT "${_oceanref_rpath_link}")
set(CMAKE_SHARED_LINKER_FLAGS_INIT "${_oceanref_rpath_link}")
set(CMAKE_MODULE_LINKER_FLAGS_INIT "${_oceanref_rpath_link}")

# pkg-config (FFTW) reads only the sysroot's .pc files and prefixes their paths with SYSROOT.
set(ENV{PKG_CONFIG_PATH} "")
set(ENV{PKG_CONFIG_LIBDIR}
    "${SYSROOT}/usr/lib/${OCEANREF_CROSS_PREFIX}/pkgconfig:${SYSROOT}/usr/lib/pkgconfig:${SYSROOT}/usr/share/pkgconfig")
set(ENV{PKG_CONFIG_SYSROOT_DIR} "${SYSROOT}")

# Test executables (ctest) run under qemu-user with the sysroot's and the toolchain's libraries.
# Threaded programs may hang under qemu-user: run them with --threads 1.
find_program(OCEANREF_QEMU_AARCH64 qemu-aarch64)
if(OCEANREF_QEMU_AARCH64)
  set(CMAKE_CROSSCOMPILING_EMULATOR "${OCEANREF_QEMU_AARCH64};-L;${SYSROOT};-E;LD_LIBRARY_PATH=${SYSROOT}/usr/lib/${OCEANREF_CROSS_PREFIX}:${SYSROOT}/lib/${OCEANREF_CROSS_PREFIX}:/usr/${OCEANREF_CROSS_PREFIX}/lib")
endif()
