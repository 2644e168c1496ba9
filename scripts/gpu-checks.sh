#!/usr/bin/env bash
# The checks for a machine with a GPU and many cores: CPU ray caster scaling with threads, GL (EGL)
# frame times of `nut render --backend gl`, and the GLSL lookup costs (gl_lookup_bench).
#
# Usage: scripts/gpu-checks.sh BUILD_DIR OUT_DIR [CITY.json ...]
# BUILD_DIR holds cli/nut and bench/gl_lookup_bench. For a GPU machine without this project's
# packages, build them without the modules that bring large libraries (LLVM through OSMesa,
# Embree) and carry the few libraries `ldd` names:
#   cmake -S . -B build-device -DNUT_BUILD_CONVERTER=OFF -DNUT_BUILD_EMBREE=OFF -DNUT_GL_OSMESA=OFF \
#         -DNUT_BUILD_TESTS=OFF && cmake --build build-device --target nut_cli gl_lookup_bench
# Writes OUT_DIR/cpu.tsv, gl.tsv, lookup.txt and machine.txt.
set -u
build=$1
out=$2
shift 2
root=$(cd "$(dirname "$0")/.." && pwd)
nut="$build/cli/nut"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$out"
{ nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv 2>/dev/null; echo "cores: $(nproc)"
  lscpu | grep "Model name"; } > "$out/machine.txt"
field() { python3 -c "import json, sys; print(json.load(open(sys.argv[1]))[sys.argv[2]])" "$1" "$2"; }
samples=("$root/samples/hni/building.png" "$root/samples/hni/facade.png" "$root/samples/hni/solids.png")

echo -e "scene\tthreads\trays_per_s" > "$out/cpu.tsv"
for scene in "${samples[@]}"; do
  for threads in 1 2 4 8 16; do
    echo "gpu-checks: cpu $scene, $threads threads" >&2
    "$nut" render "$scene" -o "$tmp/c.png" --size 1920x1080 --threads "$threads" --stats "$tmp/c.json" 2>/dev/null &&
      echo -e "$(basename "$scene")\t$threads\t$(field "$tmp/c.json" rays_per_second)" >> "$out/cpu.tsv"
  done
done

echo -e "scene\tlookup\trun\tseconds\trays_per_s" > "$out/gl.tsv"
for scene in "${samples[@]}" "$@"; do
  for lookup in exact heuristic; do
    for run in 1 2 3; do
      echo "gpu-checks: gl $scene, $lookup lookup, run $run" >&2
      "$nut" render "$scene" -o "$tmp/g.png" --backend gl --gl egl --lookup "$lookup" --size 1920x1080 \
        --stats "$tmp/g.json" 2>/dev/null &&
        echo -e "$scene\t$lookup\t$run\t$(field "$tmp/g.json" seconds)\t$(field "$tmp/g.json" rays_per_second)" >> "$out/gl.tsv"
    done
  done
done

echo "gpu-checks: gl_lookup_bench" >&2
"$build/bench/gl_lookup_bench" --gl egl > "$out/lookup.txt"
