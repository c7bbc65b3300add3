#!/usr/bin/env bash
# Installs what the example tracer needs and a fresh Debian or Ubuntu machine lacks:
# Intel Embree 3 (libembree-dev) and libpng (libpng-dev); and what examples/check-install.sh
# needs to build the examples against an installed sphera: cmake and pkg-config. Does
# nothing when all four are there. Called by README's commands and by .ci/run; the
# Makefile installs nothing.
set -euo pipefail

missing=()
[ -f /usr/include/embree3/rtcore.h ] || missing+=(libembree-dev)
[ -f /usr/include/png.h ] || missing+=(libpng-dev)
command -v cmake >/dev/null 2>&1 || missing+=(cmake)
command -v pkg-config >/dev/null 2>&1 || missing+=(pkg-config)
[ ${#missing[@]} -eq 0 ] && exit 0

echo "install-deps: installing ${missing[*]}" >&2
if [ "$(id -u)" -ne 0 ]; then
    if command -v sudo >/dev/null 2>&1; then
        sudo_cmd=(sudo)
    else
        echo "install-deps: not root and no sudo: install ${missing[*]} by hand" >&2
        exit 1
    fi
else
    sudo_cmd=()
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq "${missing[@]}" >/dev/null
