# CMake toolchain for the 64-bit ARM Linux planner (resources/bundle.sh
# linux-aarch64): Debian's cross-compiler (g++-aarch64-linux-gnu), linked fully
# static; qemu-aarch64-static runs it here (tests/python/test_portable.py).
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
set(CMAKE_FIND_ROOT_PATH /usr/aarch64-linux-gnu)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
# Quiet about what is not the project's: GCC's notes that aarch64's passing of
# some structs changed in GCC 10.1 (-Wpsabi; nothing here links code built by
# an older GCC), and a false "may be used uninitialized" in CGAL's
# Min_circle_2.h as inlined on aarch64 (an error with PLUNGE_WERROR); the
# x86-64 builds keep that warning for the project's own code.
set(CMAKE_CXX_FLAGS_INIT "-Wno-psabi -Wno-maybe-uninitialized")
