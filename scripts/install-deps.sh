#!/usr/bin/env bash
# Installs every system dependency of nut from Debian 12 packages, and the npm packages of the
# browser tests and the benchmark report into .tools/.
# Idempotent: when everything is already installed it prints nothing and exits 0.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  # core: PNG I/O, maths, CLI, JSON
  libpng-dev zlib1g-dev libzopfli-dev libglm-dev
  libcli11-dev nlohmann-json3-dev
  # the CPU ray caster's packets: portable SIMD
  libhwy-dev
  # the mesh reference renderer: Embree ray tracing
  libembree-dev libtbb-dev
  # GL back-ends: OSMesa (headless, CPU), EGL (headless GPU), GLFW windows under Xvfb
  libosmesa6-dev libegl-dev libepoxy-dev libglfw3-dev xvfb xauth
  # the streaming viewer: HTTP(S) downloads, the window's overlay
  libcurl4-openssl-dev libimgui-dev
  # the mesh converter: mesh input and checks, glTF size comparison
  libopenmesh-dev libcgal-dev libgmp-dev libmpfr-dev libmeshoptimizer-dev
  # tests, fuzzing and benchmarks
  libgtest-dev libbenchmark-dev libstb-dev clang-14 libclang-rt-14-dev
  # the benchmark report (docs/BENCHMARKS.md): plots, and Draco's encoder as a size peer
  gnuplot-nox draco
  # the city manifest checked against its JSON Schema (docs/CITY.md)
  python3-jsonschema
  # the browser viewer's tests (docs/WEB.md): headless Chromium, driven from Node.js
  chromium nodejs npm
)

# npm packages, pinned, into .tools/ (ignored by git): puppeteer-core drives the system Chromium in
# the web viewer's tests (version 24 is the last that runs on Node.js 20); gltfpack (meshoptimizer's
# packer) is the size peer of the benchmark report; meshoptimizer's decoder goes into the browser
# viewer (`nut-viewer --export-web`) to read compressed complementary meshes.
npm_packages=(puppeteer-core@24.43.1 gltfpack@1.3.0 meshoptimizer@1.3.0)
root="$(cd "$(dirname "$0")/.." && pwd)"

missing=()
for p in "${packages[@]}"; do
  # Node.js may come from elsewhere than Debian (a newer one); any node and npm will do.
  if [ "$p" = nodejs ] || [ "$p" = npm ]; then command -v "${p/nodejs/node}" >/dev/null && continue; fi
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -ne 0 ]; then
  echo "install-deps: installing ${missing[*]}" >&2
  sudo_cmd=()
  [ "$(id -u)" -ne 0 ] && sudo_cmd=(sudo)
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

for p in "${npm_packages[@]}"; do
  name="${p%@*}" version="${p##*@}"
  installed="$(node -p "require('$root/.tools/node_modules/$name/package.json').version" 2>/dev/null || true)"
  [ "$installed" = "$version" ] && continue
  echo "install-deps: installing $p into .tools/ (npm)" >&2
  npm install --silent --no-audit --no-fund --prefix "$root/.tools" "$p" >/dev/null
done
