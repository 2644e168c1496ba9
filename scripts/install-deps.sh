#!/usr/bin/env bash
# Installs every system dependency of nut from Debian 12 packages.
# Idempotent: when everything is already installed it prints nothing and exits 0.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  # core: PNG I/O, maths, CLI, JSON
  libpng-dev zlib1g-dev libzopfli-dev libglm-dev
  libcli11-dev nlohmann-json3-dev
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
  # plots of the benchmark reports (docs/BENCHMARKS.md)
  gnuplot-nox
  # the city manifest checked against its JSON Schema (docs/CITY.md)
  python3-jsonschema
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "install-deps: installing ${missing[*]}" >&2
sudo_cmd=()
[ "$(id -u)" -ne 0 ] && sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
