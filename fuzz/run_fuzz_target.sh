#!/usr/bin/env bash
# Runs one libFuzzer target over its committed corpus for a while (fuzz/README.md).
#
#   run_fuzz_target.sh [--seconds N] [--dict FILE] [--artifacts DIR] [--keep DIR] BINARY CORPUS [-- LIBFUZZER FLAGS...]
#
#   --seconds N     fuzz for N seconds (default 4; the README's long runs: 600); 0: run every
#                   input of the corpus once, no mutation (CI's regression run)
#   --dict FILE     libFuzzer dictionary
#   --artifacts DIR where a crash, timeout or out-of-memory input is written (default: a temp dir)
#   --keep DIR      keep the new inputs the run found there (default: thrown away)
#
# The committed corpus is only read: libFuzzer writes what it finds into its first corpus
# folder, which is a temporary one (or --keep). Limits: 10 s per input (a hang), 2.5 GB RSS and
# 1 GB for one allocation (ASan's own overhead included): an input that costs more is a finding
# (issue 11's counts that make a receiver allocate gigabytes). Exit code: libFuzzer's (0 = no finding).
set -euo pipefail

seconds=4
dict=""
artifacts=""
keep=""
while [ $# -gt 0 ]; do
  case "$1" in
    --seconds) seconds="$2"; shift 2 ;;
    --dict) dict="$2"; shift 2 ;;
    --artifacts) artifacts="$2"; shift 2 ;;
    --keep) keep="$2"; shift 2 ;;
    --help|-h) sed -n '2,16p' "$0"; exit 0 ;;
    *) break ;;
  esac
done
if [ $# -lt 2 ]; then
  echo "usage: run_fuzz_target.sh [--seconds N] [--dict FILE] [--artifacts DIR] [--keep DIR] BINARY CORPUS [-- FLAGS...]" >&2
  exit 2
fi
binary="$1"
corpus="$2"
shift 2
[ "${1:-}" = "--" ] && shift
if [ ! -d "$corpus" ]; then
  echo "run_fuzz_target.sh: no corpus folder $corpus (generate it: fuzz/README.md, \"Seeds\")" >&2
  exit 2
fi

tmp="$(mktemp -d "${TMPDIR:-/tmp}/minenav_fuzz.XXXXXX")"
trap 'rm -rf "$tmp"' EXIT
new="${keep:-$tmp/new}"
mkdir -p "$new"
if [ -z "$artifacts" ]; then artifacts="$tmp/artifacts"; fi
mkdir -p "$artifacts"

# 0 s: every input of the corpus once, no mutation (deterministic: the seeds and every finding
# kept as a regression input).
# (The replay's limit per input is looser: CI's unoptimised build on a shared machine takes ~6 s
# for the task planner's seed, and a replay looks for hangs, not slowness.)
if [ "$seconds" = 0 ]; then duration=(-runs=0 -timeout=30); else duration=(-max_total_time="$seconds" -timeout=10); fi
flags=("${duration[@]}" -rss_limit_mb=2560 -malloc_limit_mb=1024
       -print_final_stats=1 -artifact_prefix="$artifacts/")
[ -n "$dict" ] && flags+=(-dict="$dict")

echo "== $(basename "$binary"): ${seconds} s over $corpus ($(ls "$corpus" | wc -l) inputs)"
status=0
"$binary" "${flags[@]}" "$@" "$new" "$corpus" || status=$?
if [ $status -ne 0 ]; then
  echo "== FINDING: $(basename "$binary") exited $status; the input is in $artifacts:" >&2
  ls -l "$artifacts" >&2 || true
  echo "   reproduce: $binary <that file>; then add it to $corpus and fix (fuzz/README.md)" >&2
fi
exit $status
