#!/usr/bin/env bash
# Installs Debian's libcgal-demo (CGAL's data set) and extracts the named models into a cache
# folder outside the source tree. Idempotent: models already extracted are kept.
#
# usage: scripts/fetch-models.sh [MODEL ...]     (default: the set the tests and benchmarks use)
# env:   QF_MODELS  the cache folder (default: ~/.cache/quasiflat/models)
# Prints the cache folder on the last line.
set -euo pipefail

dest=${QF_MODELS:-$HOME/.cache/quasiflat/models}
archive=/usr/share/doc/libcgal-dev/data.tar.gz
default_models=(
  meshes/bunny00.off meshes/fandisk.off meshes/elephant.off meshes/ChineseDragon-10kv.off meshes/sphere.ply
  points_3/kitten.xyz points_3/ball.ply points_3/b9_training.ply points_3/oni.pwn points_3/sphere_20k.xyz
)
models=("$@")
[[ ${#models[@]} -eq 0 ]] && models=("${default_models[@]}")

if [[ ! -f $archive ]]; then
  echo "fetch-models: installing libcgal-demo (CGAL's data set)" >&2
  SUDO=""; [[ $(id -u) -ne 0 ]] && SUDO=sudo
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends libcgal-demo >/dev/null
fi

mkdir -p "$dest"
missing=()
for m in "${models[@]}"; do
  [[ $m == */* ]] || m=$( [[ $m == *.off ]] && echo "meshes/$m" || echo "points_3/$m")
  [[ -f "$dest/$(basename "$m")" ]] || missing+=("data/$m")
done
if [[ ${#missing[@]} -gt 0 ]]; then
  tmp=$(mktemp -d)
  trap 'rm -rf "$tmp"' EXIT
  tar -xzf "$archive" -C "$tmp" "${missing[@]}"
  for f in "${missing[@]}"; do mv "$tmp/$f" "$dest/"; done
  echo "fetch-models: extracted ${#missing[@]} model(s)" >&2
fi
echo "$dest"
