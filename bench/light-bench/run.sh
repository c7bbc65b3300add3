#!/usr/bin/env bash
# Builds the release static library (as bench/Makefile does) and the light benchmark (sphere lights, GGX, the LTC polygon light)
# against it, and runs it: first the default build, then the build for the host CPU
# (RUSTFLAGS="-C target-cpu=native", bench compiled with -march=native).
#
#   bash bench/light-bench/run.sh [--quick] [--native-only|--default-only] [bench options]
#
# Other options (--reps R, --calls N, --only NAME, --pool ID) go to the benchmark. The
# body is shared with the other benchmark: bench/bench-run.sh.
set -euo pipefail
exec bash "$(cd "$(dirname "$0")" && pwd)/../bench-run.sh" light "$@"
