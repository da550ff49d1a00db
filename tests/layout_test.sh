#!/usr/bin/env bash
# Test of scripts/check-layout: it passes on a clean made-up tree and fails, naming the file
# and the header, for each kind of broken layering.
set -euo pipefail
check="$(cd "$(dirname "$0")/.." && pwd)/scripts/check-layout"
tree=$(mktemp -d)
trap 'rm -rf "$tree"' EXIT

make_clean_tree() {
  rm -rf "${tree:?}"/*
  mkdir -p "$tree/format" "$tree/codec/common" "$tree/codec/dec" "$tree/codec/enc/fusion" \
    "$tree/codec/enc/tracking" "$tree/codec/enc/key_groups" "$tree/codec/enc/coding"
  printf '#include <vector>\n#include "format/status.h"\n' >"$tree/format/a.h"
  printf '#include "format/status.h"\n#include "codec/common/mesh.h"\n' >"$tree/codec/common/b.h"
  printf '#include "codec/dec/c.h"\n#include "meshvid/version.h"\n' >"$tree/codec/dec/c.cc"
  printf '#include "codec/common/mesh.h"\n' >"$tree/codec/enc/options.h"
  printf '#include "codec/enc/options.h"\n' >"$tree/codec/enc/summary.h"
  printf '#include "codec/enc/options.h"\n#include "codec/dec/c.h"\n' \
    >"$tree/codec/enc/fusion/f.h"
  printf '#include "codec/enc/fusion/f.h"\n#include "codec/enc/summary.h"\n' \
    >"$tree/codec/enc/key_groups/k.cc"
  printf '#include "codec/enc/summary.h"\n' >"$tree/codec/enc/coding/w.h"
  # The pipeline may include every room.
  printf '#include "codec/enc/coding/w.h"\n#include "codec/enc/key_groups/k.h"\n' \
    >"$tree/codec/enc/encoder.cc"
}

# expect_refused WHAT FILE LINE MESSAGE: appending LINE to FILE (in a clean tree) makes the
# check fail with MESSAGE in its output.
expect_refused() {
  local what=$1 file=$2 line=$3 message=$4 output
  make_clean_tree
  printf '%s\n' "$line" >>"$tree/$file"
  if output=$("$check" "$tree" 2>&1); then
    echo "FAIL: $what, and the check passed" >&2
    exit 1
  fi
  grep -qF "$message" <<<"$output" ||
    { echo "FAIL: $what: the message does not say '$message': $output" >&2; exit 1; }
}

make_clean_tree
"$check" "$tree" >/dev/null || { echo "FAIL: a clean tree was refused" >&2; exit 1; }

expect_refused "a decoder file includes an encoder header" codec/dec/c.cc \
  '#include "codec/enc/encoder.h"' 'codec/dec/c.cc: includes "codec/enc/encoder.h"'
expect_refused "an earlier room includes a later one" codec/enc/fusion/f.h \
  '#include "codec/enc/tracking/t.h"' \
  'codec/enc/fusion/f.h: includes "codec/enc/tracking/t.h", which runs back up'
expect_refused "a room includes the pipeline" codec/enc/coding/w.h \
  '#include "codec/enc/encoder.h"' 'codec/enc/coding/w.h: includes "codec/enc/encoder.h"'
expect_refused "the vocabulary includes a room" codec/enc/summary.h \
  '#include "codec/enc/coding/w.h"' \
  "codec/enc/summary.h: includes \"codec/enc/coding/w.h\", which the encoder's vocabulary"
make_clean_tree
mkdir "$tree/codec/enc/misc"
output=$("$check" "$tree" 2>&1) && { echo "FAIL: a folder that is no room passed" >&2; exit 1; }
grep -qF "codec/enc/misc/: not one of the encoder's rooms" <<<"$output" ||
  { echo "FAIL: the extra folder is not named: $output" >&2; exit 1; }
make_clean_tree
for n in 1 2 3 4 5 6 7; do printf '\n' >"$tree/codec/enc/extra$n.h"; done
output=$("$check" "$tree" 2>&1) && { echo "FAIL: 10 files at the root passed" >&2; exit 1; }
grep -qF "codec/enc/ holds 10 files at its root" <<<"$output" ||
  { echo "FAIL: the crowded root is not reported: $output" >&2; exit 1; }
echo "ok"
