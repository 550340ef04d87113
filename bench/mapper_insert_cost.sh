#!/usr/bin/env bash
# What an insert costs the live mapper, and what bounding it costs the map: the batch mapper
# (contour_mapper --log, the fleet's own settings: insert every metre or 0.3 rad, tracking the
# rest) over a recorded mission, once per option set, side by side. Per option set:
#
#   inserts  CPU s of every inserted scan's estimate, expansion and refit (POSE compute_time of
#            the scans whose status says "inserted"): the sum, the median of the last ten and
#            the largest; a live mapper at 10 Hz falls behind when these pile up beyond the
#            time the tracked scans leave over (a tracked scan costs ~0.04 s).
#   tracked  median CPU s of a tracked scan (the map's size matters, the refit not).
#   map      the final map against the true world of the run (log_tool mission-report):
#            deviation mean and max (m).
#
#   bench/mapper_insert_cost.sh --run DIR [--bin DIR] [--json-out FILE] [--variant "NAME|FLAGS"]...
#
# --run DIR: a finished run of scripts/run_demo.sh (DIR/mission.lcm and DIR/mine.json; keep one
# with run_demo.sh --out DIR, or a failed mission test's MINENAV_KEEP_MISSION_OUT=DIR).
# --variant (repeatable; default: every scan, 20 nearest, 20 nearest within 15 m): a name and
# the contour_mapper flags it adds. One mapper at a time: each takes ~1 s of CPU per 25 scans.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
run="" bin="$root/build/release/bin" json_out="" variants=()
while [ $# -gt 0 ]; do
  case "$1" in
    --run) run="$2"; shift 2 ;;
    --bin) bin="$2"; shift 2 ;;
    --json-out) json_out="$2"; shift 2 ;;
    --variant) variants+=("$2"); shift 2 ;;
    -h|--help) awk 'NR > 1 && /^#/ { print; next } NR > 1 { exit }' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "mapper_insert_cost.sh: unknown argument '$1' (--help)" >&2; exit 2 ;;
  esac
done
[ -n "$run" ] || { echo "mapper_insert_cost.sh: --run DIR is required (--help)" >&2; exit 2; }
for f in "$run/mission.lcm" "$run/mine.json"; do
  [ -s "$f" ] || { echo "mapper_insert_cost.sh: no $f" >&2; exit 2; }
done
for p in contour_mapper log_tool; do
  [ -x "$bin/$p" ] || { echo "mapper_insert_cost.sh: no $bin/$p (build build/release first)" >&2; exit 2; }
done
[ ${#variants[@]} -gt 0 ] || variants=("every scan (thesis)|" "20 nearest|--mapper.fit-scans 20"
                                        "20 nearest, 15 m (fleet)|--mapper.fit-scans 20 --mapper.local-fit-radius 15")
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

rows=()
k=0
for v in "${variants[@]}"; do
  name="${v%%|*}" flags="${v#*|}"
  echo "== $name: contour_mapper --log $run/mission.lcm $flags" >&2
  # shellcheck disable=SC2086  # the flags are words
  "$bin/contour_mapper" --log "$run/mission.lcm" --insert-min-translation 1.0 --insert-min-rotation 0.3 \
    --final-refinement-rounds 0 $flags --map-out "$work/$k.json" --log-out "$work/$k.lcm" 2> "$work/$k.log" ||
    { tail -n 5 "$work/$k.log" >&2; exit 3; }
  "$bin/log_tool" mission-report --log "$run/mission.lcm" --world "$run/mine.json" --map "$work/$k.json" \
    --report-out "$work/$k.md" --json-out "$work/$k.report.json" 2> /dev/null ||
    { echo "mapper_insert_cost.sh: log_tool mission-report failed on $name" >&2; exit 3; }
  rows+=("$name|$work/$k.lcm|$work/$k.report.json")
  k=$((k + 1))
done

python3 - "$json_out" "$run" "${rows[@]}" <<'PY'
import json, struct, sys

def pose_costs(path):
    """(inserted, tracked) CPU seconds from the POSE messages of an LCM log (pose_estimate_t)."""
    data = open(path, "rb").read()
    i, inserted, tracked = 0, [], []
    while i + 28 <= len(data):
        sync, _, _, cl, dl = struct.unpack(">IqqII", data[i:i + 28])
        if sync != 0xEDA1DA01:
            raise SystemExit(f"{path}: not an LCM log at byte {i}")
        channel = data[i + 28:i + 28 + cl].decode()
        d = data[i + 28 + cl:i + 28 + cl + dl]
        i += 28 + cl + dl
        if channel != "POSE":
            continue
        o = 8 + 16                                   # fingerprint, utime, scan_id
        o += 4 + struct.unpack(">I", d[o:o + 4])[0]  # source
        o += 24 + 72 + 8 + 12 + 1                    # pose, covariance, residual, counts, converged
        n = struct.unpack(">I", d[o:o + 4])[0]
        status = d[o + 4:o + 3 + n].decode()
        o += 4 + n
        cost = struct.unpack(">f", d[o:o + 4])[0]
        (inserted if "inserted" in status else tracked).append(cost)
    return inserted, tracked

def median(v):
    v = sorted(v)
    return v[len(v) // 2] if v else float("nan")

out, table = [], []
for row in sys.argv[3:]:
    name, lcm, report = row.split("|")
    ins, trk = pose_costs(lcm)
    dev = json.load(open(report))["map_accuracy"]
    r = {"variant": name, "inserts": len(ins), "insert_cpu_s_sum": sum(ins),
         "insert_cpu_s_last10_median": median(ins[-10:]), "insert_cpu_s_max": max(ins, default=0.0),
         "tracked_cpu_s_median": median(trk), "deviation_mean_m": dev["deviation_mean_m"],
         "deviation_max_m": dev["deviation_max_m"]}
    out.append(r)
print(f"run: {sys.argv[2]}")
print(f"{'variant':28s} {'inserts':>7s} {'CPU s sum':>9s} {'last 10 med':>11s} {'max':>6s} {'tracked med':>11s} {'dev mean m':>10s} {'dev max m':>9s}")
for r in out:
    print(f"{r['variant']:28s} {r['inserts']:7d} {r['insert_cpu_s_sum']:9.1f} {r['insert_cpu_s_last10_median']:11.2f} "
          f"{r['insert_cpu_s_max']:6.2f} {r['tracked_cpu_s_median']:11.3f} {r['deviation_mean_m']:10.3f} {r['deviation_max_m']:9.3f}")
if sys.argv[1]:
    json.dump({"run": sys.argv[2], "variants": out}, open(sys.argv[1], "w"), indent=1)
PY
