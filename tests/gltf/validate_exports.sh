#!/bin/sh
# CTest: `meshvid export` to .glb on the golden files (one key group; three key groups, whole
# and a range starting and ending inside key groups), each checked by the Khronos glTF
# validator, which must report zero errors. Skips (77) without node or the validator.
# Usage: validate_exports.sh MESHVID VALIDATOR_DIR GOLDEN_DIR WORK_DIR
set -eu
meshvid=$1 validator=$2 golden=$3 work=$4
if ! command -v node >/dev/null 2>&1; then
  echo "node is not installed (scripts/setup installs it): skipped"
  exit 77
fi
mkdir -p "$work"
"$meshvid" export -q "$golden/sphere.v1.mvid" -o "$work/v1.glb"
"$meshvid" export -q "$golden/sphere.v2.mvid" -o "$work/v2.glb"
"$meshvid" export -q "$golden/sphere.v2.mvid" -o "$work/v2-range.glb" --frames 3:11
exec node "$(dirname "$0")/validate.mjs" "$validator" "$work/v1.glb" "$work/v2.glb" \
  "$work/v2-range.glb"
