#!/usr/bin/env bash
# Configures and builds the core alone (nut, packer, scene and the `nut` command) with every
# optional module off, checks that its link line and the linked binary name no CGAL, Embree or GL
# library, and runs `nut info`, `validate` and a CPU `render` with it. meshoptimizer is allowed:
# scene decodes meshopt-compressed GLB complements (EXT_meshopt_compression) for every reader.
# Usage: scripts/check-core-build.sh [BUILD_DIR]   (default build-core)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-build-core}
jobs=$(nproc)
echo "core build: configuring $build with NUT_BUILD_CONVERTER, NUT_BUILD_EMBREE and NUT_BUILD_GL off" >&2
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DNUT_WERROR=ON -DNUT_BUILD_CONVERTER=OFF \
  -DNUT_BUILD_EMBREE=OFF -DNUT_BUILD_GL=OFF -DNUT_BUILD_TESTS=OFF -DNUT_BUILD_BENCH=OFF > /dev/null
cmake --build "$build" -j "$jobs" --target nut_cli > /dev/null
forbidden='cgal|embree|tbb|gmp|mpfr|openmesh|osmesa|libGL|libEGL|libOpenGL|glfw|epoxy'
link_line="$build/cli/CMakeFiles/nut_cli.dir/link.txt"
if grep -Eio "$forbidden" "$link_line"; then
  echo "core build: error: $link_line names an optional module's library (above)" >&2
  exit 1
fi
if ldd "$build/cli/nut" | grep -Ei "$forbidden"; then
  echo "core build: error: $build/cli/nut loads an optional module's library (above)" >&2
  exit 1
fi
nut="$build/cli/nut"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$nut" info "$root/samples/hni/building.png" > /dev/null
"$nut" validate "$root/samples/hni/building.png" > /dev/null
"$nut" render "$root/samples/hni/building.png" -o "$out/building.png" --size 64x36 2> /dev/null
if "$nut" convert "$root/samples/obj/house.obj" -o "$out/house.png" 2> /dev/null; then
  echo "core build: error: convert ran in a build without the converter" >&2
  exit 1
fi
echo "core build: nut links only the core's libraries; info, validate and render ran" >&2
