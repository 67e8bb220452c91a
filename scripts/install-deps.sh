#!/usr/bin/env bash
# Installs every Debian package quasiflat needs to build, test and run. Idempotent and
# non-interactive; when everything is present it only runs dpkg-query and exits (well under a second).
set -euo pipefail

packages=(
  # toolchain
  build-essential cmake pkg-config ninja-build
  # the design card's libraries
  libtinygltf-dev nlohmann-json3-dev libstb-dev   # glTF writer/loader (+ its JSON and image deps)
  libdraco-dev                                    # Draco mesh/point compression
  libzstd-dev                                     # zstd for Basis Universal (third_party/basis_universal): UASTC KTX2
                                                  # (meshoptimizer, laz-perf and Basis Universal are built from third_party/)
  libwebp-dev                                     # WebP textures (EXT_texture_webp): encoder (gltf/webp.cpp), decoder (runtime_gl/webp_image.cpp)
  libopenimageio-dev openimageio-tools            # image I/O and image algorithms
  libopenexr-dev                                  # EXR difference images
  libeigen3-dev                                   # sparse matrices, eigen-solvers
  libpcl-dev                                      # k-nearest neighbours (KdTree)
  libcgal-dev                                     # 2D Delaunay triangulations
  libssl-dev                                      # SHA-256 (OpenSSL libcrypto): batch content keys
  libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri libglx-mesa0  # headless OpenGL on Mesa llvmpipe
  libx11-dev xvfb xauth                           # qf-render view's window, tested under Xvfb
  fonts-dejavu-core                               # captions of the demo's side-by-side picture
  # tests
  libgtest-dev googletest libbenchmark-dev
  python3-jsonschema                              # validates our JSON outputs against schemas/ in tests
  clang libclang-rt-14-dev                        # libFuzzer + sanitizer runtimes: scripts/fuzz.sh, tests/fuzz
  assimp-testmodels                               # glTF 2.0 and OBJ test models, valid and malformed: the assets test
  chromium                                        # three.js and Babylon.js renders (scripts/three-render, babylon-render): engine-truth tests, fidelity league
  blender python3-numpy                           # Blender 3.4 (background mode) and its glTF importer's numpy, which Debian's package
                                                  # does not depend on (without it every import fails): the engine_blender test
  python3-pil                                     # with python3-numpy: scripts/octahedral_peer.py (the far and fidelity benchmarks' peer)
  slurm-wlm munge python3-yaml                    # the slurm test: a one-node cluster runs scripts/slurm/; docs/farm.md's Kubernetes YAML
)

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done

# Node.js runs the Khronos glTF-Validator in the tests; most machines have it already.
command -v node >/dev/null && command -v npm >/dev/null || missing+=(nodejs npm)

if [[ ${#missing[@]} -gt 0 ]]; then
  echo "install-deps: installing ${#missing[@]} package(s): ${missing[*]}"
  SUDO=""
  if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# npm packages, pinned by their package-lock.json: the glTF validator, and three.js and Babylon.js,
# each with playwright-core (which drives Debian's chromium; it downloads no browser of its own).
scripts_dir="$(cd "$(dirname "$0")" && pwd)"
for pkg in validate-gltf/node_modules/gltf-validator three-render/node_modules/three three-render/node_modules/playwright-core \
           babylon-render/node_modules/@babylonjs/core babylon-render/node_modules/@babylonjs/loaders babylon-render/node_modules/playwright-core; do
  dir="$scripts_dir/${pkg%%/node_modules/*}"
  if [[ ! -f "$scripts_dir/$pkg/package.json" ]]; then
    echo "install-deps: installing ${dir##*/} (npm ci)"
    npm ci --prefix "$dir" --no-audit --no-fund --loglevel=error
  fi
done

# glTF-Transform (library and CLI) and gltfpack with quasiflat's extensions, pinned by
# tools/gltf-transform-qf/package-lock.json: the gltf_transform_qf test and docs/toolchain.md.
tools_dir="$(dirname "$scripts_dir")/tools"
for pkg in gltf-transform-qf/node_modules/@gltf-transform/cli gltf-transform-qf/node_modules/gltfpack; do
  dir="$tools_dir/${pkg%%/node_modules/*}"
  if [[ ! -f "$tools_dir/$pkg/package.json" ]]; then
    echo "install-deps: installing ${dir##*/} (npm ci)"
    npm ci --prefix "$dir" --no-audit --no-fund --loglevel=error
  fi
done
