#!/usr/bin/env bash
# Installs the Debian packages cutaway needs to build, test and run.
# Idempotent and quiet: when everything is present it prints nothing and
# touches nothing. Used by `make demo`, `make test` and CI alike; `make bench`
# passes --bench for the VTK comparison's packages as well, `make fuzz` --fuzz
# for clang and libFuzzer, `make lint` --lint for clang-tidy.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  glslang-tools
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers
  libglm-dev libopenexr-dev nlohmann-json3-dev libcli11-dev
  libgtest-dev zlib1g-dev libpng-dev python3-jsonschema
  libgdcm-dev libgdcm-tools python3-pydicom python3-numpy python3-nibabel
  libtinygltf-dev openexr openimageio-tools
)
# The benchmark's comparison with VTK's CPU ray caster (bench/vtk_bench.py)
# needs VTK's Python module and an X server for its render window; its
# profile of lavapipe's generated code (bench/jit_profile.py) perf, gdb and
# objdump.
# The fuzz targets (fuzz/) need clang and its libFuzzer runtime
# (libclang_rt.fuzzer-x86_64.a, in libclang-rt-14-dev on Debian 12).
for option in "$@"; do
  case "$option" in
    --bench) packages+=(python3-vtk9 xvfb xauth linux-perf gdb binutils) ;;
    --fuzz) packages+=(clang libclang-rt-dev) ;;
    --lint) packages+=(clang-tidy) ;;
    *) echo "usage: $0 [--bench] [--fuzz] [--lint]" >&2; exit 2 ;;
  esac
done

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done
[[ ${#missing[@]} -eq 0 ]] && exit 0

echo "cutaway: installing missing Debian packages: ${missing[*]}"
sudo=""
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "cutaway: need root (or sudo) to install: ${missing[*]}" >&2; exit 1; }
  sudo="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "cutaway: packages installed"
