#!/usr/bin/env bash
# sphera's main job: installs what is missing (Embree 3, libpng), builds the release
# static library and the tracer, and writes the speed-versus-error report to report/
# (report/index.html, report/report.md; the table is also printed). Arguments go to
# report.py: --quick for the 30-second version that CI runs, --help for the rest.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
bash "$here/install-deps.sh"
make -s -C "$here" >&2
exec python3 "$here/report.py" "$@"
