#!/usr/bin/env bash
# Installs the Debian 12 packages glint needs to build, test and benchmark.
# Idempotent: packages already present are skipped, and apt-get runs only when
# something is missing. Needs root (or sudo) only in that case.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  ccache                   # compiles each unchanged file once across builds and fresh clones
  libyaml-cpp-dev          # scene files
  libopenexr-dev           # EXR read and written through OpenEXR
  libspng-dev              # PNG read with libspng (PNG written by glint over zlib)
  libjpeg62-turbo-dev      # JPEG textures through libjpeg-turbo
  libopenimageio-dev       # the long tail of texture formats (module libglint_oiio.so)
  openimageio-tools        # idiff / oiiotool, used by tests and docs
  libtbb-dev               # parallel tile loop
  libcli11-dev             # command line
  libtinyobjloader-dev     # OBJ + MTL import
  libtinygltf-dev nlohmann-json3-dev  # glTF 2.0 import (tinygltf's JSON)
  libdraco-dev libmeshoptimizer-dev   # glTF compressed meshes (KHR_draco_mesh_compression, EXT_meshopt_compression)
  draco                               # draco_transcoder: the Draco test files
  libembree-dev            # the Embree backend (--accel embree) and its benchmark
  libfmt-dev               # formatting
  libopenvdb-dev libboost-dev  # grid media (smoke, clouds) read from .vdb files (its headers need Boost)
  libopenmpi-dev openmpi-bin   # distributed rendering (mpirun -np N glint render), and its tests
  zlib1g-dev               # gzip-compressed PLY meshes (.ply.gz, as pbrt-v4 scenes ship them)
  python3                  # scripts/make_gltf_scene.py (the glTF test scene)
  pybind11-dev python3-dev python3-numpy python3-pytest  # the Python module (python/) and its tests
  libgtest-dev libgmock-dev
  libbenchmark-dev
  clang libclang-rt-14-dev # libFuzzer and the sanitizers: `make fuzz`, run by `make test`
)
# Optional groups, not needed to build or test:
# peers and timer for `make bench`, OpenCV for the denoiser's classical baseline (bench/denoise.sh), Xvfb for the Blender viewport test (make test-blender),
if [[ "${GLINT_BENCH_DEPS:-0}" == 1 ]]; then
  packages+=(povray hyperfine blender xvfb time python3-opencv)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
sudo_cmd=()
if [[ $(id -u) -ne 0 ]]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
