#!/usr/bin/env bash
# log_tool export-mcap checked by an independent reader (npm @mcap/core, logger/mcap_check.mjs)
# on the operator's view's known log (viewer_test_log), with one undecodable message added:
# it must be skipped and counted, the rest exported. Installs node/npm packages when missing.
#   logger/export_mcap_test.sh BIN_DIR WORK_DIR
set -euo pipefail
bin="$1"; work="$2"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/.." && pwd)"
source "$root/scripts/common.sh"
minenav_npm_ci "$root/tests/js"
[ -d "$root/tests/js/node_modules/@mcap/core" ] || { echo "export_mcap_test: FAILED: npm @mcap/core is missing" >&2; exit 1; }

rm -rf "$work"; mkdir -p "$work"; cd "$work"
"$root/viewer/testing/make_known_log.sh" "$bin"
"$bin/log_tool" info --json known.lcm > info.json
# One more event on POSE that does not decode (an LCM event: magic, number, time, lengths, channel, data).
python3 - known.lcm bad.lcm <<'PY'
import struct, sys
data = open(sys.argv[1], "rb").read()
bad = struct.pack(">IqqII", 0xEDA1DA01, 999, 1000000002500000, 4, 3) + b"POSE" + b"\x01\x02\x03"
open(sys.argv[2], "wb").write(data + bad)
PY
# Small chunks: several chunks and their indexes are read back.
"$bin/log_tool" export-mcap bad.lcm known.mcap --chunk-kb 16 2> export.log
cat export.log
grep -q "1 messages skipped (do not decode); the first: POSE at byte" export.log
head -c 8 known.mcap | od -An -c | grep -q "M   C   A   P   0"
MCAP_MIN_CHUNKS=4 node "$here/mcap_check.mjs" known.mcap info.json
echo "export_mcap_test: passed"
