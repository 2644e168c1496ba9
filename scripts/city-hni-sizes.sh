#!/usr/bin/env bash
# scripts/city-hni-sizes.sh [BUILD]: rewrites bench/data/city_hni_sizes.txt, packer_bench's atlas
# input: the HNI sizes of `nut city --count 2116 --layout grid --seed 1` in manifest order (the
# order the viewer streams them in), read from each PNG's IHDR.
set -euo pipefail
build=${1:-build}
root="$(cd "$(dirname "$0")/.." && pwd)"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$build/cli/nut" city --count 2116 --layout grid --seed 1 --out "$work/city" --quiet
python3 - "$work/city" "$root/bench/data/city_hni_sizes.txt" <<'PY'
import json, os, struct, sys
city, out = sys.argv[1], sys.argv[2]
lines = ["# The HNI sizes (width height, texels) of `nut city --count 2116 --layout grid --seed 1`, in",
         "# manifest order, the order the viewer streams them in: packer_bench's atlas input. Rewrite with",
         "# scripts/city-hni-sizes.sh."]
for b in json.load(open(os.path.join(city, "city.json")))["buildings"]:
    with open(os.path.join(city, b["hni"]), "rb") as f:
        width, height = struct.unpack(">II", f.read(24)[16:24])
    lines.append(f"{width} {height}")
with open(out + ".tmp", "w") as f:
    f.write("\n".join(lines) + "\n")
os.replace(out + ".tmp", out)
PY
echo "city-hni-sizes: wrote $root/bench/data/city_hni_sizes.txt" >&2
