#!/usr/bin/env bash
# Installs sphera for C and C++ programs: builds the release static library and copies
# it, the header, a pkg-config file and a CMake package into a prefix.
#
#   PREFIX=$HOME/.local bash install.sh     # default PREFIX: /usr/local
#
# writes
#   $PREFIX/lib/libsphera.a
#   $PREFIX/include/sphera.h
#   $PREFIX/lib/pkgconfig/sphera.pc                    pkg-config --cflags --libs sphera
#   $PREFIX/lib/cmake/sphera/spheraConfig.cmake        find_package(sphera): sphera::sphera
#   $PREFIX/lib/cmake/sphera/spheraConfigVersion.cmake
# SHARED=1 also installs a shared library (Linux, GNU ld): lib/libsphera.so.X.Y.Z with the
# soname libsphera.so.X.Y before 1.0 (every 0.x release may change the ABI) and
# libsphera.so.X from 1.0 on, the links libsphera.so.X.Y (or .X) and libsphera.so, and
# the CMake target sphera::sphera_shared. `-lsphera` then links it rather than the
# static library; sphera::sphera stays the static library. It exports the sphera_*
# functions only.
# DESTDIR=/staging puts the files under /staging$PREFIX (for packagers); the files
# still name $PREFIX. The static library leaves only memcpy, memset, memcmp, bcmp and
# abort to the C library (the core is no_std: no threads, no dynamic loading, no
# allocator, and its maths comes from the libm crate inside it), so no -lpthread or
# -ldl; the pkg-config and CMake files add -lm as the header's link line does, which
# keeps the link line valid should a target's build ever call the system libm.
# Environment: CARGO (default cargo), CARGO_TARGET_DIR (default target/install: its
# own directory, so that the library is built alone, without the tools' `std` feature).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
prefix="${PREFIX:-/usr/local}"
case "$prefix" in
    /*) ;;
    *) echo "install.sh: PREFIX must be an absolute path, not '$prefix'" >&2; exit 2 ;;
esac
prefix="${prefix%/}"
destination="${DESTDIR:-}$prefix"
target_dir="${CARGO_TARGET_DIR:-$root/target/install}"

echo "install.sh: building the release static library" >&2
(cd "$root" && CARGO_TARGET_DIR="$target_dir" "${CARGO:-cargo}" build --release -p sphera --lib)
library="$target_dir/release/libsphera.a"
[ -f "$library" ] || { echo "install.sh: the build did not produce $library" >&2; exit 1; }

# The version of the header, which tools/src/generators/header.rs writes from Cargo.toml.
version="$(sed -n 's/^#define SPHERA_VERSION_STRING "\(.*\)"$/\1/p' "$root/include/sphera.h")"
[ -n "$version" ] || { echo "install.sh: no SPHERA_VERSION_STRING in include/sphera.h" >&2; exit 1; }
major="${version%%.*}"
rest="${version#*.}"
minor="${rest%%.*}"

# The host's pointer width in bytes, which the library is built for.
pointer_bytes=$(( $(getconf LONG_BIT) / 8 ))

mkdir -p "$destination/lib/pkgconfig" "$destination/lib/cmake/sphera" "$destination/include"
install -m 644 "$library" "$destination/lib/libsphera.a"
install -m 644 "$root/include/sphera.h" "$destination/include/sphera.h"

if [ "${SHARED:-0}" = 1 ]; then
    if [ "$(uname -s)" != Linux ]; then
        echo "install.sh: SHARED=1 is supported on Linux only" >&2
        exit 2
    fi
    if [ "$major" = 0 ]; then soname="libsphera.so.$major.$minor"; else soname="libsphera.so.$major"; fi
    map="$(mktemp)"
    trap 'rm -f "$map"' EXIT
    printf '{ global: sphera_*; local: *; };\n' >"$map"
    # The whole archive, its unused sections dropped, symbols other than sphera_* hidden.
    "${CC:-cc}" -shared -o "$destination/lib/libsphera.so.$version" -Wl,-soname,"$soname" \
        -Wl,--version-script="$map" -Wl,--gc-sections -Wl,-z,defs -s \
        -Wl,--whole-archive "$library" -Wl,--no-whole-archive -lm
    chmod 755 "$destination/lib/libsphera.so.$version"
    [ "$soname" = "libsphera.so.$version" ] || ln -sf "libsphera.so.$version" "$destination/lib/$soname"
    ln -sf "$soname" "$destination/lib/libsphera.so"
fi

cat > "$destination/lib/pkgconfig/sphera.pc" <<PC
prefix=$prefix
libdir=\${prefix}/lib
includedir=\${prefix}/include

Name: sphera
Description: Sampling and shading of polygonal, sphere and virtual spherical Gaussian lights
Version: $version
Cflags: -I\${includedir}
Libs: -L\${libdir} -lsphera -lm
PC

cat > "$destination/lib/cmake/sphera/spheraConfig.cmake" <<'CMAKE'
# The CMake package of sphera (written by install.sh): find_package(sphera) defines the
# imported target sphera::sphera, the static library libsphera.a with its header
# directory and its one dependency, libm. Relocatable: paths are relative to this file.
get_filename_component(_sphera_prefix "${CMAKE_CURRENT_LIST_DIR}/../../.." ABSOLUTE)
if(NOT TARGET sphera::sphera)
  add_library(sphera::sphera STATIC IMPORTED)
  set_target_properties(sphera::sphera PROPERTIES
    IMPORTED_LOCATION "${_sphera_prefix}/lib/libsphera.a"
    INTERFACE_INCLUDE_DIRECTORIES "${_sphera_prefix}/include"
    IMPORTED_LINK_INTERFACE_LANGUAGES "C")
  if(UNIX)
    set_property(TARGET sphera::sphera PROPERTY INTERFACE_LINK_LIBRARIES m)
  endif()
endif()
# The shared library, when install.sh installed one (SHARED=1).
if(NOT TARGET sphera::sphera_shared AND EXISTS "${_sphera_prefix}/lib/libsphera.so")
  get_filename_component(_sphera_shared "${_sphera_prefix}/lib/libsphera.so" REALPATH)
  add_library(sphera::sphera_shared SHARED IMPORTED)
  set_target_properties(sphera::sphera_shared PROPERTIES
    IMPORTED_LOCATION "${_sphera_shared}"
    INTERFACE_INCLUDE_DIRECTORIES "${_sphera_prefix}/include")
  unset(_sphera_shared)
endif()
unset(_sphera_prefix)
CMAKE

cat > "$destination/lib/cmake/sphera/spheraConfigVersion.cmake" <<CMAKE
# The version of the installed sphera (written by install.sh). A request for
# MAJOR.MINOR is met when the major versions agree and, before 1.0, the minor versions
# too (every 0.x release may change the ABI), from 1.0 on when the installed minor
# version is at least the requested one: the rule of sphera_check_version().
set(PACKAGE_VERSION "$version")
set(PACKAGE_VERSION_COMPATIBLE FALSE)
if(NOT PACKAGE_FIND_VERSION)
  set(PACKAGE_VERSION_COMPATIBLE TRUE)
elseif(PACKAGE_FIND_VERSION_MAJOR STREQUAL "$major")
  if("$major" STREQUAL "0")
    if(PACKAGE_FIND_VERSION_MINOR STREQUAL "$minor" AND NOT PACKAGE_FIND_VERSION VERSION_GREATER PACKAGE_VERSION)
      set(PACKAGE_VERSION_COMPATIBLE TRUE)
    endif()
  elseif(NOT PACKAGE_FIND_VERSION VERSION_GREATER PACKAGE_VERSION)
    set(PACKAGE_VERSION_COMPATIBLE TRUE)
  endif()
endif()
if(PACKAGE_FIND_VERSION AND PACKAGE_FIND_VERSION VERSION_EQUAL PACKAGE_VERSION)
  set(PACKAGE_VERSION_EXACT TRUE)
endif()
# The library is built for the host: refuse it to a project of another pointer width.
if(CMAKE_SIZEOF_VOID_P AND NOT CMAKE_SIZEOF_VOID_P STREQUAL "$pointer_bytes")
  set(PACKAGE_VERSION "\${PACKAGE_VERSION} ($((pointer_bytes * 8))-bit)")
  set(PACKAGE_VERSION_UNSUITABLE TRUE)
endif()
CMAKE

echo "install.sh: installed sphera $version into $destination" >&2
