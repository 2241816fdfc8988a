#!/usr/bin/env bash
# Builds Polyslice from its GitHub source at a pinned commit into vendor/ (git-ignored):
# it is not on the npm registry (neither is @jgphilpott/polyconvert), so its sources are
# read from git checkouts, compiled with the pinned CoffeeScript of package-lock.json, and
# linked as node_modules/@jgphilpott/*. Nothing of theirs is committed here.
#
#   POLYSLICE_GIT=/path/to/polyslice.git POLYCONVERT_GIT=... ./setup.sh
#
# Each defaults to a clone from GitHub. Polytree (which Polyslice's `slice` needs for
# `Polytree.sliceIntoLayers`) is the 0.1.9 that Polyslice 26.4.0's package-lock.json pins,
# fetched from the npm registry and checked against that lock's integrity; or, where that
# registry does not hold it, a polytree source tree (its app/*.coffee, scripts/bundle.sh and
# package.json) given as POLYTREE_DIR=..., compiled and bundled as its package.json does
# (`coffee -cb`, then scripts/bundle.sh). MESH.md says which source the results used.
# POLYTREE_DIR=none links a stand-in instead, enough for compare.mjs (the five shapes call
# Polyslice's infill generators, which never reach Polytree) but not for a mesh's `slice`.
set -euo pipefail
cd "$(dirname "$0")"
POLYSLICE_COMMIT=5057a95f51232a6f8213d4303d9f5dfd2f828102 # 26.4.0, as ../shared/anchors beside the repository
POLYCONVERT_COMMIT=cd25da0
POLYTREE_VERSION=0.1.9 # and its integrity, from Polyslice 26.4.0's package-lock.json
POLYTREE_INTEGRITY=sha512-I2FMDYm3h4uC+BowXg6lVuOU4qXltUSQW0K3EtwCH+W7yDdCi0kt/nr2LYBfdI0Gn92KAs/8yslB2EZsS2YfTw==
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
npx --no-install coffee -cb vendor/polyslice/src/
mkdir -p vendor/polytree
if [ "${POLYTREE_DIR:-}" = none ]; then
  echo '{"name": "@jgphilpott/polytree", "version": "0.0.0-stand-in", "main": "index.js"}' >vendor/polytree/package.json
  printf '%s\n' 'class Polytree { static sliceIntoLayers() { throw new Error("Polytree stand-in (setup.sh POLYTREE_DIR=none): no mesh slicing"); } }' 'module.exports = Polytree;' 'module.exports.Polytree = Polytree;' >vendor/polytree/index.js
elif [ -n "${POLYTREE_DIR:-}" ]; then
  cp -r "$POLYTREE_DIR"/package.json "$POLYTREE_DIR"/app "$POLYTREE_DIR"/scripts vendor/polytree/
  npx --no-install coffee -cb vendor/polytree/app/
  (cd vendor/polytree && bash scripts/bundle.sh)
else
  tarball=$(cd vendor && npm pack --silent "@jgphilpott/polytree@$POLYTREE_VERSION") || {
    echo "@jgphilpott/polytree@$POLYTREE_VERSION is not on this npm registry: give a polytree source tree as POLYTREE_DIR=... (see MESH.md)" >&2
    exit 1
  }
  got="sha512-$(openssl dgst -sha512 -binary "vendor/$tarball" | base64 -w0)"
  [ "$got" = "$POLYTREE_INTEGRITY" ] || { echo "polytree $POLYTREE_VERSION: integrity $got, expected $POLYTREE_INTEGRITY" >&2; exit 1; }
  tar -xzf "vendor/$tarball" -C vendor/polytree --strip-components=1
fi
mkdir -p node_modules/@jgphilpott
for p in polyslice polyconvert polytree; do
  ln -sfn "../../vendor/$p" "node_modules/@jgphilpott/$p"
done
# Polyslice's own require('three') etc. resolve from here.
ln -sfn ../node_modules vendor/node_modules
echo "Polyslice ${POLYSLICE_COMMIT:0:8} ready in vendor/polyslice"
