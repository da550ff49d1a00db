#!/usr/bin/env bash
# Makes the inputs the ArmBlockEncode tests of cli_encode_test share: FRAMES frames of the
# simulated arm-block scene (OUT/cap) and their encode (OUT/arm.mvid, OUT/summary.json, and what
# the encode printed in OUT/encode-stderr.txt). ctest runs it once per run, before those tests
# (the fixture arm_block_inputs); a test process run alone runs it into its own folder.
# Usage: make_arm_block_inputs.sh MESHVID OUT FRAMES
set -euo pipefail
meshvid=$1 out=$2 frames=$3
rm -rf "$out"
mkdir -p "$out"
"$meshvid" simulate scene:arm-block -o "$out/cap" --frames "0:$frames" -q
if ! "$meshvid" encode "$out/cap/manifest.json" -o "$out/arm.mvid" --levels 2 \
  --summary-json "$out/summary.json" 2>"$out/encode-stderr.txt"; then
  cat "$out/encode-stderr.txt" >&2
  exit 1
fi
