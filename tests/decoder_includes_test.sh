#!/usr/bin/env bash
# Test of scripts/check-decoder-includes: it passes on a clean decoder tree and fails, naming
# the file and the header, when a decoder file includes an encoder header.
set -euo pipefail
check="$(dirname "$0")/../scripts/check-decoder-includes"
tree=$(mktemp -d)
trap 'rm -rf "$tree"' EXIT
mkdir -p "$tree/format" "$tree/codec/common" "$tree/codec/dec" "$tree/codec/enc"
printf '#include <vector>\n#include "format/status.h"\n' >"$tree/format/a.h"
printf '#include "format/status.h"\n#include "codec/common/mesh.h"\n' >"$tree/codec/common/b.h"
printf '#include "codec/dec/c.h"\n#include "meshvid/version.h"\n' >"$tree/codec/dec/c.cc"
printf '#include "codec/dec/c.h"\n' >"$tree/codec/enc/e.cc"  # the encoder may include anything
"$check" "$tree" >/dev/null || { echo "FAIL: a clean tree was refused" >&2; exit 1; }

printf '#include "codec/enc/encoder.h"\n' >>"$tree/codec/dec/c.cc"
if output=$("$check" "$tree" 2>&1); then
  echo "FAIL: codec/dec/c.cc includes an encoder header and the check passed" >&2
  exit 1
fi
grep -q 'codec/dec/c.cc: includes "codec/enc/encoder.h"' <<<"$output" ||
  { echo "FAIL: the message does not name the file and header: $output" >&2; exit 1; }
echo "ok"
