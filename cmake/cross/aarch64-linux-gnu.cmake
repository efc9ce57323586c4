# Cross-build of the ROS-free engine for arm64 (scripts/check_arm64.sh):
# Debian's aarch64 toolchain (g++-aarch64-linux-gnu) with its own C library,
# and the arm64 OpenCV, zlib and googletest unpacked into BOWG_ARM64_SYSROOT
# by scripts/arm64_sysroot.sh. Tests run under qemu-user.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)

if(NOT BOWG_ARM64_SYSROOT)
  message(FATAL_ERROR "set BOWG_ARM64_SYSROOT to the folder scripts/arm64_sysroot.sh filled")
endif()
# try_compile projects see only the variables listed here.
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES BOWG_ARM64_SYSROOT)

# Libraries, headers and package files from the unpacked arm64 packages only;
# programs (the build tools) from the host.
set(CMAKE_FIND_ROOT_PATH ${BOWG_ARM64_SYSROOT})
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)

# The sysroot holds the libraries OpenCV itself needs (TBB, LAPACK, ...): the
# linker resolves them there, qemu loads them from there.
set(bowg_arm64_libs
    ${BOWG_ARM64_SYSROOT}/usr/lib/aarch64-linux-gnu:${BOWG_ARM64_SYSROOT}/lib/aarch64-linux-gnu)
set(CMAKE_EXE_LINKER_FLAGS_INIT "-Wl,-rpath-link,${bowg_arm64_libs}")
set(CMAKE_SHARED_LINKER_FLAGS_INIT "-Wl,-rpath-link,${bowg_arm64_libs}")
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-aarch64 -L ${BOWG_ARM64_SYSROOT})

# Debian's arm64 OpenCVConfig.cmake lists every OpenCV module and fails on
# the ones not unpacked: the engine's five modules are declared here instead.
set(OpenCV_DIR ${CMAKE_CURRENT_LIST_DIR}/opencv CACHE PATH "arm64 OpenCV config" FORCE)
