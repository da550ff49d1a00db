#!/bin/sh
# The WebAssembly decoder (web/build, made by scripts/setup) against the native one, on .mvid
# files: native_reference writes what the native decoder makes of each; decoder_test.mjs runs
# the WebAssembly decoder under Node.js on them all; browser_test.mjs runs it in headless
# Chromium with WebCodecs on the AV1 ones, and on AV1 transcodes of the others (`meshvid
# transcode`), which themselves must be refused with an error in the page; player_test.mjs
# plays the last file in the player (web/player), and streams a 10 MB file made of it
# (repeat_mvid) through a throttled server.
# Usage: run_web_tests.sh NATIVE_REFERENCE REPEAT_MVID MESHVID PROJECT_ROOT WORK_DIR FILE.mvid...
# Exits 77 (skipped) when the WebAssembly decoder is not built.
set -eu
native_reference=$1 repeat_mvid=$2 meshvid=$3 root=$4 work=$5
shift 5
if [ ! -f "$root/web/build/meshvid_wasm.mjs" ] || ! command -v node >/dev/null 2>&1; then
  echo "skipped: the WebAssembly decoder is not built (scripts/setup builds it into web/build)"
  exit 77
fi
rm -rf "$work"
mkdir -p "$work"
node_pairs="" browser_files="" unsupported=""
for file in "$@"; do
  name=$(basename "$file" .mvid)
  cp "$file" "$work/$name.mvid"
  "$native_reference" "$work/$name.mvid" "$work/$name.bin"
  node_pairs="$node_pairs $work/$name.mvid $work/$name.bin"
  if "$meshvid" info "$file" --json - | grep -q '"codec": *"av1"'; then
    browser_files="$browser_files,$name.mvid"
  else
    unsupported="$unsupported,$name.mvid"
    "$meshvid" transcode "$file" --codec av1 -o "$work/$name.av1.mvid" -q
    "$native_reference" "$work/$name.av1.mvid" "$work/$name.av1.bin"
    browser_files="$browser_files,$name.av1.mvid"
  fi
done
here=$(dirname "$0")
# shellcheck disable=SC2086  # the pairs are paths without spaces, split on purpose
node "$here/decoder_test.mjs" "$root/web/build" $node_pairs
browser=${MESHVID_CHROMIUM:-/usr/bin/chromium}
if [ ! -x "$browser" ]; then
  echo "the browser half is skipped: no Chromium at $browser (scripts/setup installs it)"
  exit 0
fi
node "$here/browser_test.mjs" "$root" "$work" --files "${browser_files#,}" \
  --unsupported "${unsupported#,}"
# The player, on the last file (the fresh encode), and on 80 copies of it one after another.
last=$(basename "$file" .mvid)
"$repeat_mvid" "$work/$last.mvid" 80 "$work/long.mvid"
node "$here/player_test.mjs" "$root" "$work" "$meshvid" "$last.mvid" long.mvid
