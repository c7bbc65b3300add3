#!/usr/bin/env bash
# Installs what the example tracer needs and a fresh Debian or Ubuntu machine lacks:
# Intel Embree 3 (libembree-dev) and libpng (libpng-dev). Does nothing when both are
# there. Called by README's commands and by .ci/run; the Makefile installs nothing.
set -euo pipefail

missing=()
[ -f /usr/include/embree3/rtcore.h ] || missing+=(libembree-dev)
[ -f /usr/include/png.h ] || missing+=(libpng-dev)
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
