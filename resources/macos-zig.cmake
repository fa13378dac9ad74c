# CMake toolchain for the macOS planners (resources/bundle.sh macos-arm64 and
# macos-x86_64): Zig's clang, libc++ and macOS stubs (Zig from the npm
# registry, checked and unpacked by bundle.sh), cross-compiling from Linux.
# bundle.sh sets PLUNGE_ZIG_BIN, a folder of its wrappers around `zig c++
# -target ARCH-macos`, `zig ar` and `zig ranlib`, and PLUNGE_MACOS_ARCH
# (aarch64 or x86_64); environment variables, as CMake's own test builds read
# this file again.
if(NOT DEFINED ENV{PLUNGE_ZIG_BIN} OR NOT DEFINED ENV{PLUNGE_MACOS_ARCH})
  message(FATAL_ERROR "macos-zig.cmake: set PLUNGE_ZIG_BIN and PLUNGE_MACOS_ARCH (resources/bundle.sh does)")
endif()
set(CMAKE_SYSTEM_NAME Darwin)
set(CMAKE_SYSTEM_PROCESSOR $ENV{PLUNGE_MACOS_ARCH})
set(CMAKE_CXX_COMPILER $ENV{PLUNGE_ZIG_BIN}/$ENV{PLUNGE_MACOS_ARCH}-macos-c++)
set(CMAKE_AR $ENV{PLUNGE_ZIG_BIN}/zig-ar CACHE FILEPATH "")
set(CMAKE_RANLIB $ENV{PLUNGE_ZIG_BIN}/zig-ranlib CACHE FILEPATH "")
# No Xcode here: no sysroot to ask xcrun for, no -arch flags (the target says it).
set(CMAKE_OSX_SYSROOT "" CACHE PATH "")
set(CMAKE_OSX_ARCHITECTURES "" CACHE STRING "")
# Boost 1.74's container_hash uses std::unary_function, which Zig's libc++ 16
# removed from C++17.
set(CMAKE_CXX_FLAGS_INIT "-DBOOST_NO_CXX98_FUNCTION_BASE")
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
