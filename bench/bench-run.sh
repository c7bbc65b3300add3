#!/usr/bin/env bash
# The body of bench/polygon-bench/run.sh and bench/light-bench/run.sh: builds
# the release static library (as bench/Makefile does) and the named benchmark
# (bench/NAME-bench/NAME_bench.c) against it, and runs it: first the default build,
# then the build for the host CPU (RUSTFLAGS="-C target-cpu=native", bench compiled with
# -march=native).
#
#   bash bench/bench-run.sh NAME [--quick] [--native-only|--default-only] [bench options]
#
# Other options (--reps R, --calls N, --only NAME, --pool ID) go to the benchmark.
set -euo pipefail

name="${1:?bench-run.sh: the bench name first: polygon or light}"
shift
here="$(cd "$(dirname "$0")" && pwd)/$name-bench"
root="$(cd "$here/../.." && pwd)"
cargo="${CARGO:-cargo}"
cc="${CC:-gcc}"

builds="default native"
bench_args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --default-only) builds="default" ;;
    --native-only) builds="native" ;;
    --reps | --calls | --only | --pool)
      [ $# -ge 2 ] || { echo "$name-bench/run.sh: $1 needs a value" >&2; exit 2; }
      bench_args+=("$1" "$2")
      shift
      ;;
    *) bench_args+=("$1") ;;
  esac
  shift
done

out="$root/target/$name-bench"
mkdir -p "$out"

for build in $builds; do
  if [ "$build" = default ]; then
    label="default build"
    target_dir="$root/target/c-abi"
    rustflags="${RUSTFLAGS:-}"
    cflags=()
  else
    label="target-cpu=native"
    target_dir="$root/target/c-abi-native"
    rustflags="${RUSTFLAGS:+$RUSTFLAGS }-C target-cpu=native"
    cflags=(-march=native)
  fi
  echo "== $label"
  # The core alone in its own target directory, so that the `std` feature that the
  # workspace's tools turn on is not unified into it (see bench/Makefile).
  (cd "$root" && env -u CARGO_BUILD_TARGET RUSTFLAGS="$rustflags" CARGO_TARGET_DIR="$target_dir" \
    "$cargo" build --release -p sphera --lib --manifest-path "$root/Cargo.toml" 1>&2)
  program="$out/${name}_bench-$build"
  "$cc" -O2 -std=c99 -Wall -Wextra -Werror -pedantic ${cflags[@]+"${cflags[@]}"} -I"$root/include" \
    -o "$program" "$here/${name}_bench.c" "$target_dir/release/libsphera.a" -lm -lpthread -ldl
  "$program" ${bench_args[@]+"${bench_args[@]}"}
  echo
done
