#!/usr/bin/env bash
# Builds Polyslice from its GitHub source at a pinned commit into vendor/ (git-ignored):
# it is not on the npm registry (neither is @jgphilpott/polyconvert or /polytree, which it
# requires), so its sources are read from git checkouts, compiled with the pinned
# CoffeeScript of package-lock.json, and linked as node_modules/@jgphilpott/*.
# Nothing of theirs is committed here.
#
#   POLYSLICE_GIT=/path/to/polyslice.git POLYCONVERT_GIT=... POLYTREE_GIT=... ./setup.sh
#
# Each defaults to a clone from GitHub.
set -euo pipefail
cd "$(dirname "$0")"
POLYSLICE_COMMIT=5057a95f51232a6f8213d4303d9f5dfd2f828102 # 26.4.0, as ../shared/anchors beside the repository
POLYCONVERT_COMMIT=cd25da0
POLYTREE_COMMIT=547444c
npm ci --no-audit --no-fund >/dev/null
rm -rf vendor && mkdir -p vendor
get() { # name, git dir or "", commit, paths (its sources only: large test meshes are not needed)
  local dir=$2
  if [ -z "$dir" ]; then
    dir=vendor/$1.git
    git clone --quiet --bare "https://github.com/jgphilpott/$1" "$dir"
  fi
  mkdir -p "vendor/$1"
  git --git-dir="$dir" archive "$3" -- "${@:4}" | tar -x -C "vendor/$1"
}
get polyslice "${POLYSLICE_GIT:-}" "$POLYSLICE_COMMIT" package.json src
get polyconvert "${POLYCONVERT_GIT:-}" "$POLYCONVERT_COMMIT" package.json polyconvert.js
get polytree "${POLYTREE_GIT:-}" "$POLYTREE_COMMIT" package.json polytree.js
npx --no-install coffee -cb vendor/polyslice/src/
mkdir -p node_modules/@jgphilpott
for p in polyslice polyconvert polytree; do
  ln -sfn "../../vendor/$p" "node_modules/@jgphilpott/$p"
done
# Polyslice's own require('three') etc. resolve from here.
ln -sfn ../node_modules vendor/node_modules
echo "Polyslice ${POLYSLICE_COMMIT:0:8} ready in vendor/polyslice"
