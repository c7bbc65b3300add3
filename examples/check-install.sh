#!/usr/bin/env bash
# Installs sphera into a temporary prefix with ../install.sh and builds the examples
# against it twice, with CMake's find_package(sphera) (CMakeLists.txt here) and with
# `pkg-config --cflags --libs sphera`, runs the four programs and prints their output
# under "== <way>: <program>" lines (tools/tests/examples.rs checks the numbers). Also
# checks the CMake package's version rule and, on Linux, the shared library of
# `SHARED=1 install.sh` (quad_light linked against it through pkg-config). Needs cmake and pkg-config (CI installs them
# with bench/install-deps.sh). Exits non-zero on the first failure.
#
#   bash examples/check-install.sh             # KEEP=1 keeps the temporary directory
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
for tool in cmake pkg-config "${CC:-cc}" "${CXX:-c++}"; do
    command -v "$tool" >/dev/null 2>&1 || {
        echo "check-install: $tool is missing (bash bench/install-deps.sh installs cmake and pkg-config)" >&2
        exit 1
    }
done
work="$(mktemp -d)"
if [ "${KEEP:-0}" = 1 ]; then
    echo "check-install: keeping $work" >&2
else
    trap 'rm -rf "$work"' EXIT
fi
prefix="$work/prefix"

PREFIX="$prefix" bash "$root/install.sh"
for file in lib/libsphera.a include/sphera.h lib/pkgconfig/sphera.pc \
    lib/cmake/sphera/spheraConfig.cmake lib/cmake/sphera/spheraConfigVersion.cmake; do
    [ -f "$prefix/$file" ] || { echo "check-install: $file was not installed" >&2; exit 1; }
done

# 1. CMake: find_package(sphera) and the imported target sphera::sphera.
cmake -S "$here" -B "$work/cmake" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_C_FLAGS="-Wall -Wextra -Werror -pedantic" \
    -DCMAKE_CXX_FLAGS="-Wall -Wextra -Werror -pedantic" >"$work/cmake.log" 2>&1 \
    || { cat "$work/cmake.log" >&2; exit 1; }
cmake --build "$work/cmake" >>"$work/cmake.log" 2>&1 || { cat "$work/cmake.log" >&2; exit 1; }
for program in quad_light sphere_light_ggx; do
    echo "== cmake: $program"
    "$work/cmake/$program"
done

# 2. pkg-config.
export PKG_CONFIG_PATH="$prefix/lib/pkgconfig${PKG_CONFIG_PATH:+:$PKG_CONFIG_PATH}"
read -r -a flags <<<"$(pkg-config --cflags --libs sphera)"
echo "pkg-config --cflags --libs sphera: ${flags[*]}" >&2
"${CC:-cc}" -std=c99 -O2 -Wall -Wextra -Werror -pedantic "$here/quad_light.c" "${flags[@]}" \
    -o "$work/quad_light"
"${CXX:-c++}" -std=c++11 -O2 -Wall -Wextra -Werror -pedantic "$here/sphere_light_ggx.cpp" \
    "${flags[@]}" -o "$work/sphere_light_ggx"
for program in quad_light sphere_light_ggx; do
    echo "== pkg-config: $program"
    "$work/$program"
done

# 3. The version rule of spheraConfigVersion.cmake: the installed MAJOR.MINOR is found,
# the next major version is not.
version="$(pkg-config --modversion sphera)"
major="${version%%.*}"
rest="${version#*.}"
minor="${rest%%.*}"
find_version() {
    mkdir -p "$work/version-$1"
    printf 'cmake_minimum_required(VERSION 3.13)\nproject(v NONE)\nfind_package(sphera %s REQUIRED CONFIG)\n' \
        "$1" >"$work/version-$1/CMakeLists.txt"
    cmake -S "$work/version-$1" -B "$work/version-$1/build" -DCMAKE_PREFIX_PATH="$prefix" \
        >"$work/version-$1/log" 2>&1
}
find_version "$major.$minor" || { cat "$work/version-$major.$minor/log" >&2; exit 1; }
if find_version "$((major + 1)).0"; then
    echo "check-install: find_package(sphera $((major + 1)).0) accepted version $version" >&2
    exit 1
fi
echo "== versions: find_package(sphera $major.$minor) found $version, $((major + 1)).0 refused"

# 4. The shared library (Linux): quad_light through pkg-config links libsphera.so and
# runs with it.
if [ "$(uname -s)" = Linux ]; then
    shared="$work/shared"
    PREFIX="$shared" SHARED=1 bash "$root/install.sh"
    read -r -a flags <<<"$(PKG_CONFIG_PATH="$shared/lib/pkgconfig" pkg-config --cflags --libs sphera)"
    "${CC:-cc}" -std=c99 -O2 -Wall -Wextra -Werror -pedantic "$here/quad_light.c" "${flags[@]}" \
        -o "$work/quad_light_shared"
    needed="$(readelf -d "$work/quad_light_shared" | sed -n 's/.*(NEEDED).*\[\(libsphera[^]]*\)\].*/\1/p')"
    soname="$(readelf -d "$shared/lib/libsphera.so" | sed -n 's/.*(SONAME).*\[\(.*\)\].*/\1/p')"
    if [ -z "$needed" ] || [ "$needed" != "$soname" ] || [ ! -e "$shared/lib/$soname" ]; then
        echo "check-install: quad_light needs '$needed', the shared library's soname is '$soname'" >&2
        exit 1
    fi
    exported="$(nm -D --defined-only "$shared/lib/libsphera.so" | awk '{print $3}' | grep -vc '^sphera_' || true)"
    if [ "$exported" != 0 ]; then
        echo "check-install: the shared library exports $exported symbols besides sphera_*" >&2
        exit 1
    fi
    echo "== shared ($soname): quad_light"
    LD_LIBRARY_PATH="$shared/lib" "$work/quad_light_shared"
fi
