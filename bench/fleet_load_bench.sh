#!/usr/bin/env bash
# The whole fleet under load: the README's main job (scripts/run_demo.sh: fleet/mission.fleet
# under the supervisor, in a private network namespace, log_tool record recording every message)
# for --duration seconds, then Ctrl-C (SIGINT to the supervisor: it stops the fleet in order
# and the report is still written). Measures:
#
#   processes  every fleet process (the children of `fleet run`, and the supervisor itself),
#              sampled every --period s from /proc: mean CPU % (utime+stime), RSS at 1 minute
#              and at the end, and the RSS slope over the second half of the run (KB/min,
#              least squares): "flat" as a number. A restarted process (new pid) starts a new
#              series (its own row, marked).
#   loss       the recorded log (OUT/mission.lcm), per channel: messages, gaps and missing in
#              seq / scan_id (log_tool info); HEARTBEAT has one seq per process and is
#              counted per process here. The signed (command) channels are judged by their
#              authentication trailers instead: every signing process numbers all its signed
#              messages in one sequence (common/message_auth.h), so a gap there is a lost
#              command on any of its channels, whatever the channel's own seq means (two
#              publishers on DRIVE_COMMAND; CUT_TASK's seq is the coordinator's task id).
#   UDP        per channel the largest message (bytes) against the receive buffer the fleet
#              asks for (recv_buf_size=4194304, tests/bus/private_net.sh) and LCM's udpm limits
#              (one datagram up to 65499 bytes of channel + payload, else 65487-byte
#              fragments); margin = buffer / largest. Also measured, every --udp-period s: each
#              process's socket receive queue (its peak) and the kernel's drop count, from
#              the namespace's /proc/PID/net/udp; the buffer the kernel granted (ss -m).
#
#   bench/fleet_load_bench.sh [--bin DIR] [--duration S] [--fast F] [--small] [--period S]
#                             [--udp-period S] [--port P] [--out DIR] [--json-out FILE]
#
# --bin: the programs (default build/release/bin, built by run_demo.sh when missing).
# --duration (default 600 s): from the supervisor's start to the Ctrl-C; a mission that ends
# sooner ends the run sooner (said in the table). --fast F (default 2): run_demo.sh's speed
# factor; the full two-pillar section at 2 keeps the fleet exploring (driving, scanning at
# 10 Hz, mapping, planning) for longer than 10 minutes. --out DIR keeps the run (the log is
# about 100 MB for 10 minutes); by default a temporary folder, removed at the end.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
bin="" duration=600 fast=2 small=0 period=5 udp_period=0.5 port=7791 out="" json_out=""
while [ $# -gt 0 ]; do
  case "$1" in
    --bin) bin="$2"; shift 2 ;;
    --duration) duration="$2"; shift 2 ;;
    --fast) fast="$2"; shift 2 ;;
    --small) small=1; shift ;;
    --period) period="$2"; shift 2 ;;
    --udp-period) udp_period="$2"; shift 2 ;;
    --port) port="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --json-out) json_out="$2"; shift 2 ;;
    -h|--help) awk 'NR > 1 && /^#/ { print; next } NR > 1 { exit }' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "fleet_load_bench: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
number='^[0-9]+([.][0-9]+)?$'
[[ "$duration" =~ $number ]] && awk "BEGIN { exit !($duration >= 10) }" ||
  { echo "fleet_load_bench: --duration must be a number of seconds >= 10" >&2; exit 2; }
[[ "$period" =~ $number ]] && awk "BEGIN { exit !($period >= 0.5) }" ||
  { echo "fleet_load_bench: --period must be a number of seconds >= 0.5" >&2; exit 2; }
[[ "$udp_period" =~ $number ]] && awk "BEGIN { exit !($udp_period >= 0.05) }" ||
  { echo "fleet_load_bench: --udp-period must be a number of seconds >= 0.05" >&2; exit 2; }
demo_args=(--fast "$fast" --port "$port")  # run_demo.sh checks --fast and --port
[ $small -eq 1 ] && demo_args+=(--small)
if [ -n "$bin" ]; then
  [ -x "$bin/log_tool" ] || { echo "fleet_load_bench: --bin $bin has no log_tool" >&2; exit 2; }
  bin="$(cd "$bin" && pwd)"
  demo_args+=(--bin "$bin")
else
  bin="$root/build/release/bin"
fi
keep=1
if [ -z "$out" ]; then out="$(mktemp -d)"; keep=0; fi
mkdir -p "$out"
out="$(cd "$out" && pwd)"
[ $keep -eq 0 ] && trap 'rm -rf "$out"' EXIT
demo_args+=(--out "$out")

echo "== the fleet: scripts/run_demo.sh ${demo_args[*]} (Ctrl-C after $duration s)"
"$root/scripts/run_demo.sh" "${demo_args[@]}" >"$out/demo.txt" 2>&1 &
demo=$!

# The sampler: finds `fleet run .../mission.fleet --out OUT`, samples its children and its
# namespace's UDP sockets, sends SIGINT at --duration, stops when the supervisor has ended.
python3 - "$out" "$duration" "$period" "$udp_period" "$port" >"$out/sampler.txt" 2>&1 <<'PY' &
import os, re, signal, subprocess, sys, time, json
out, duration, period, udp_period = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])
bus_port = "%04X" % int(sys.argv[5])  # the bus's sockets (not the send sockets)
tck = os.sysconf("SC_CLK_TCK")

def read(path):
    try:
        with open(path, "rb") as f:
            return f.read()
    except OSError:
        return None

def stat(pid):  # (comm, ppid, utime+stime ticks, start ticks)
    s = read(f"/proc/{pid}/stat")
    if s is None: return None
    s = s.decode(errors="replace")
    comm = s[s.index("(") + 1:s.rindex(")")]
    f = s[s.rindex(")") + 2:].split()
    return comm, int(f[1]), int(f[11]) + int(f[12]), int(f[19])

def rss_kb(pid):
    s = read(f"/proc/{pid}/status")
    if s is None: return None
    m = re.search(rb"VmRSS:\s+(\d+) kB", s)
    return int(m.group(1)) if m else 0

def find_supervisor():
    for p in os.listdir("/proc"):
        if not p.isdigit(): continue
        c = read(f"/proc/{p}/cmdline")
        if not c: continue
        a = c.split(b"\0")
        if len(a) > 2 and a[0].endswith(b"/fleet") and a[1] == b"run" and out.encode() in a and \
           a[a.index(out.encode()) - 1] == b"--out":
            return int(p)
    return None

t0 = time.time()
sup = None
while sup is None:
    if time.time() - t0 > 600: print("no supervisor found in 600 s", file=sys.stderr); sys.exit(3)
    sup = find_supervisor()
    time.sleep(0.2)
start = time.monotonic()
print(f"supervisor pid {sup}", flush=True)
procs = open(os.path.join(out, "samples.csv"), "w")
procs.write("t,pid,name,cpu_ticks,rss_kb\n")
udp = open(os.path.join(out, "udp.csv"), "w")
udp.write("t,pid,inode,rx_queue,drops\n")
inode_pid = {}
stopped_at = None
ended = "duration"
next_proc = 0.0
ss_done = False
snmp_first = snmp_now = None

def children():
    kids = []
    for p in os.listdir("/proc"):
        if not p.isdigit(): continue
        st = stat(int(p))
        # tee: run_demo.sh's copy of the status table, not a fleet process
        if st and st[1] == sup and st[0] != "tee": kids.append((int(p), st))
    return kids

while True:
    t = time.monotonic() - start
    if read(f"/proc/{sup}/stat") is None:
        if stopped_at is None: ended = "mission ended"; stopped_at = t
        break
    if t >= next_proc:
        next_proc += period
        rows = [(sup, stat(sup))] + children()
        inode_pid = {}
        for pid, st in rows:
            if st is None: continue
            r = rss_kb(pid)
            if r is None: continue
            name = "fleet (supervisor)" if pid == sup else st[0]
            procs.write(f"{t:.2f},{pid},{name},{st[2]},{r}\n")
            try:
                for fd in os.listdir(f"/proc/{pid}/fd"):
                    l = os.readlink(f"/proc/{pid}/fd/{fd}")
                    if l.startswith("socket:["): inode_pid[l[8:-1]] = pid
            except OSError:
                pass
        procs.flush()
        snmp = read(f"/proc/{sup}/net/snmp")
        if snmp:
            l = [x.split() for x in snmp.decode().splitlines() if x.startswith("Udp:")]
            if len(l) >= 2:
                snmp_now = dict(zip(l[0][1:], map(int, l[1][1:])))
                if snmp_first is None: snmp_first = snmp_now
        if not ss_done and t > 30:
            ss_done = True
            for cmd, name in ((["ss", "-u", "-a", "-m", "-p"], "ss.txt"), (["cat", "/proc/sys/net/core/rmem_max"], "rmem_max")):
                r = subprocess.run(["nsenter", "-t", str(sup), "-n"] + cmd, capture_output=True, text=True)
                open(os.path.join(out, name), "w").write(r.stdout + r.stderr)
    u = read(f"/proc/{sup}/net/udp")
    if u:
        for line in u.decode().splitlines()[1:]:
            f = line.split()
            if len(f) < 13 or not f[1].endswith(":" + bus_port): continue
            rx = int(f[4].split(":")[1], 16)
            pid = inode_pid.get(f[9])
            if pid is None: continue
            udp.write(f"{t:.2f},{pid},{f[9]},{rx},{f[12]}\n")
    if stopped_at is None and t >= duration:
        stopped_at = t
        print(f"SIGINT to the supervisor at {t:.1f} s", flush=True)
        os.kill(sup, signal.SIGINT)
    time.sleep(udp_period)
udp.close(); procs.close()
json.dump({"supervisor": sup, "stopped_at": stopped_at, "ended": ended, "udp_snmp_first": snmp_first,
           "udp_snmp_last": snmp_now}, open(os.path.join(out, "run.json"), "w"))
print(f"{ended} at {stopped_at:.1f} s", flush=True)
PY
sampler=$!
stopped=0
trap 'stopped=1' INT TERM
wait $sampler || { echo "fleet_load_bench: the sampler failed:" >&2; cat "$out/sampler.txt" >&2; }
demo_status=0
wait $demo || demo_status=$?
[ $stopped -eq 1 ] && { echo "fleet_load_bench: stopped" >&2; exit 130; }
grep -E '^== (stopped|the mission ended|the fleet ended)' "$out/demo.txt" || true
[ -s "$out/mission.lcm" ] || { echo "fleet_load_bench: no log recorded ($out/mission.lcm; see $out/demo.txt)" >&2; exit 3; }
"$bin/log_tool" info --json "$out/mission.lcm" >"$out/info.json" 2>"$out/info.err" ||
  echo "fleet_load_bench: log_tool info reports errors ($out/info.err)" >&2

python3 - "$out" "$duration" "$json_out" "$(grep -c '^processor' /proc/cpuinfo)" <<'PY'
import csv, json, os, struct, sys
out, duration, json_out, ncpu = sys.argv[1], float(sys.argv[2]), sys.argv[3], int(sys.argv[4])
tck = os.sysconf("SC_CLK_TCK")
run = json.load(open(os.path.join(out, "run.json")))
stop = run["stopped_at"]
buf = 4194304  # recv_buf_size of every process's URL (tests/bus/private_net.sh)
SHORT_MAX, FRAG_PAYLOAD = 65499, 65487  # LCM udpm (Linux): one datagram, else fragments

def slope(points):  # least squares, KB per minute
    n = len(points)
    if n < 3: return None
    mt = sum(t for t, _ in points) / n; mr = sum(r for _, r in points) / n
    d = sum((t - mt) ** 2 for t, _ in points)
    return None if d == 0 else 60.0 * sum((t - mt) * (r - mr) for t, r in points) / d

# Processes: one series per pid, samples up to the Ctrl-C (the shutdown is not the run).
series = {}
for r in csv.DictReader(open(os.path.join(out, "samples.csv"))):
    t = float(r["t"])
    if t > stop: continue
    series.setdefault(int(r["pid"]), {"name": r["name"], "s": []})["s"].append((t, int(r["cpu_ticks"]), int(r["rss_kb"])))
names = {}
for pid, s in series.items(): names.setdefault(s["name"], []).append(pid)
procs = []
for pid, s in sorted(series.items(), key=lambda kv: (kv[1]["name"] != "fleet (supervisor)", kv[1]["name"], kv[1]["s"][0][0])):
    pts = s["s"]
    t0, c0, _ = pts[0]; t1, c1, r1 = pts[-1]
    cpu = 100.0 * (c1 - c0) / tck / (t1 - t0) if t1 > t0 else None
    r60 = min(pts, key=lambda p: abs(p[0] - (t0 + 60)))[2]
    half = [(t, r) for t, _, r in pts if t >= t0 + (t1 - t0) / 2]
    procs.append({"process": s["name"], "pid": pid, "restarted": len(names[s["name"]]) > 1 and pid != names[s["name"]][0],
                  "from_s": round(t0, 1), "to_s": round(t1, 1), "samples": len(pts),
                  "cpu_percent": None if cpu is None else round(cpu, 1),
                  "rss_kb_1min": r60, "rss_kb_end": r1, "rss_kb_max": max(p[2] for p in pts),
                  "rss_slope_kb_per_min_2nd_half": None if slope(half) is None else round(slope(half), 1)})

# UDP: each process's socket receive queue (bytes of datagrams waiting) and the kernel's drops.
pid_name = {pid: s["name"] for pid, s in series.items()}
udp = {}
for r in csv.DictReader(open(os.path.join(out, "udp.csv"))):
    u = udp.setdefault(int(r["pid"]), {"peak": 0, "drops": 0, "samples": 0})
    u["peak"] = max(u["peak"], int(r["rx_queue"])); u["drops"] = max(u["drops"], int(r["drops"])); u["samples"] += 1
granted = {}
if os.path.exists(os.path.join(out, "ss.txt")):
    import re
    for line in open(os.path.join(out, "ss.txt")):
        m = re.search(r"pid=(\d+)", line); b = re.search(r"\brb(\d+)", line)
        if m and b: granted[int(m.group(1))] = max(granted.get(int(m.group(1)), 0), int(b.group(1)))
# ss prints the socket line and its skmem on one line with -p -m; fall back to pairs of lines.
if not granted and os.path.exists(os.path.join(out, "ss.txt")):
    lines = open(os.path.join(out, "ss.txt")).read().splitlines()
    for a, b in zip(lines, lines[1:]):
        m = re.search(r"pid=(\d+)", a); rb = re.search(r"\brb(\d+)", b)
        if m and rb and "pid=" in a and a.count("pid=") == 1:
            granted[int(m.group(1))] = max(granted.get(int(m.group(1)), 0), int(rb.group(1)))

# The log: per channel the largest message (its UDP size: channel + NUL + payload).
largest = {}
path = os.path.join(out, "mission.lcm")
with open(path, "rb") as f:
    while True:
        h = f.read(28)
        if len(h) < 28: break
        magic, _, _, clen, dlen = struct.unpack(">IqqII", h)
        if magic != 0xEDA1DA01: break
        ch = f.read(clen).decode(errors="replace")
        data = f.read(dlen)
        size = clen + 1 + dlen
        if size > largest.get(ch, (0,))[0]: largest[ch] = (size, dlen)
        if ch == "HEARTBEAT" and dlen >= 28:  # heartbeat_t: fingerprint, utime, seq, process
            seq = struct.unpack(">q", data[16:24])[0]
            n = struct.unpack(">i", data[24:28])[0]
            proc = data[28:28 + n - 1].decode(errors="replace")
            hb = largest.setdefault(("HB", proc), {"count": 0, "gaps": 0, "missing": 0, "first": seq, "last": None, "ooo": 0})
            hb["count"] += 1
            if hb["last"] is not None:
                if seq > hb["last"] + 1: hb["gaps"] += 1; hb["missing"] += seq - hb["last"] - 1
                elif seq <= hb["last"]: hb["ooo"] += 1
            hb["last"] = seq
info = json.load(open(os.path.join(out, "info.json")))
loss = []
for c in info["channels"]:
    ch = c["channel"]
    size = largest.get(ch, (0, 0))[0]
    row = {"channel": ch, "type": c["type"], "messages": c["count"], "rate_hz": round(c["rate_hz"], 2),
           "sequence_field": c["sequence_field"] or None, "gaps": c["sequence_gaps"] if c["sequence_field"] else None,
           "missing": c["missing"] if c["sequence_field"] else None,
           "out_of_order": c["out_of_order"] if c["sequence_field"] else None,
           "largest_bytes": size, "datagrams": 1 if size <= SHORT_MAX else -(-(size) // FRAG_PAYLOAD),
           "margin": round(buf / size, 1) if size else None}
    if c.get("signed_senders", 0) > 0 and c.get("unsigned_count", 0) == 0:
        row["sequence_field"] = "signed: trailer"
        row["gaps"] = row["missing"] = row["out_of_order"] = None  # judged per sender, below
        row["signed_senders"] = c["signed_senders"]
    if ch == "HEARTBEAT":
        per = {k[1]: v for k, v in largest.items() if isinstance(k, tuple) and k[0] == "HB"}
        row["per_process"] = {p: {k: v[k] for k in ("count", "gaps", "missing", "ooo")} for p, v in sorted(per.items())}
        row["gaps"] = sum(v["gaps"] for v in per.values()); row["missing"] = sum(v["missing"] for v in per.values())
        row["out_of_order"] = sum(v["ooo"] for v in per.values()); row["sequence_field"] = "seq per process"
    loss.append(row)
loss.sort(key=lambda r: -r["largest_bytes"])

print(f"\nrun: {run['ended']} at {stop:.0f} s (--duration {duration:.0f}); samples every few s; {ncpu} cores")
print(f"\n{'process':<20} {'pid':>7} {'from s':>7} {'CPU %':>6} {'RSS 1 min KB':>13} {'RSS end KB':>11} {'RSS max KB':>11} {'2nd half KB/min':>16}")
for p in procs:
    mark = " (restarted)" if p["restarted"] else ""
    sl = "-" if p["rss_slope_kb_per_min_2nd_half"] is None else f"{p['rss_slope_kb_per_min_2nd_half']:+.1f}"
    print(f"{p['process'] + mark:<20} {p['pid']:>7} {p['from_s']:>7.0f} {p['cpu_percent'] if p['cpu_percent'] is not None else '-':>6} "
          f"{p['rss_kb_1min']:>13} {p['rss_kb_end']:>11} {p['rss_kb_max']:>11} {sl:>16}")
tot = sum(p["cpu_percent"] or 0 for p in procs)
print(f"{'all':<20} {'':>7} {'':>7} {tot:>6.1f}   (of {100 * ncpu} % on {ncpu} cores)")

print(f"\n{'channel':<18} {'messages':>9} {'rate Hz':>8} {'seq field':<16} {'gaps':>5} {'missing':>8} {'loss %':>7} {'largest B':>10} {'datagrams':>9} {'margin':>7}")
for r in loss:
    lp = "-" if r["missing"] is None else f"{100.0 * r['missing'] / (r['messages'] + r['missing']):.2f}"
    print(f"{r['channel']:<18} {r['messages']:>9} {r['rate_hz']:>8} {r['sequence_field'] or '-':<16} "
          f"{'-' if r['gaps'] is None else r['gaps']:>5} {'-' if r['missing'] is None else r['missing']:>8} {lp:>7} "
          f"{r['largest_bytes']:>10} {r['datagrams']:>9} {r['margin'] if r['margin'] else '-':>7}")
senders = info.get("senders", [])
total_missing = sum(r["missing"] or 0 for r in loss) + sum(s["missing"] for s in senders)
total = sum(r["messages"] for r in loss)
print(f"{'all':<18} {total:>9} {'':>8} {'':<16} {'':>5} {total_missing:>8}   (with the signed senders' below)")
if senders:
    print(f"\nsigned senders: one trailer sequence over each process's signed channels (a gap = a command lost on any of them)")
    print(f"{'sender':<18} {'messages':>9} {'trailer seq':>18} {'gaps':>5} {'missing':>8} {'out of order':>13}  channels")
    for s in senders:
        rng = f"{s['first_sequence']} .. {s['last_sequence']}"
        print(f"{s['sender']:<18} {s['count']:>9} {rng:>18} {s['sequence_gaps']:>5} {s['missing']:>8} {s['out_of_order']:>13}  "
              + ",".join(s["channels"]))
hb = [r for r in loss if r["channel"] == "HEARTBEAT"]
if hb and hb[0].get("per_process"):
    print("HEARTBEAT per process: " + ", ".join(f"{p} {v['count']} ({v['missing']} missing)" for p, v in hb[0]["per_process"].items()))
big = loss[0] if loss else None
if big:
    print(f"\nlargest message: {big['channel']} {big['largest_bytes']} B ({big['datagrams']} datagram(s) of LCM udpm: "
          f"one up to {SHORT_MAX} B, else fragments of {FRAG_PAYLOAD} B); receive buffer asked {buf} B: margin {big['margin']}x")
rmem = open(os.path.join(out, "rmem_max")).read().strip() if os.path.exists(os.path.join(out, "rmem_max")) else "?"
print(f"net.core.rmem_max in the namespace: {rmem}")
a, b = run.get("udp_snmp_first"), run.get("udp_snmp_last")
if a and b:
    d = {k: b[k] - a[k] for k in b if k in a}
    print(f"the namespace's UDP counters over the run (/proc/net/snmp): InDatagrams {d.get('InDatagrams')}, "
          f"RcvbufErrors {d.get('RcvbufErrors')}, InErrors {d.get('InErrors')}")
print(f"\n{'process':<20} {'pid':>7} {'rcvbuf granted':>15} {'peak rx queue B':>16} {'kernel drops':>13}")
udp_rows = []
for pid, u in sorted(udp.items(), key=lambda kv: pid_name.get(kv[0], "?")):
    g = granted.get(pid)
    udp_rows.append({"process": pid_name.get(pid, "?"), "pid": pid, "rcvbuf_granted": g, "peak_rx_queue_bytes": u["peak"],
                     "kernel_drops": u["drops"], "samples": u["samples"]})
    print(f"{pid_name.get(pid, '?'):<20} {pid:>7} {g if g else '-':>15} {u['peak']:>16} {u['drops']:>13}")
if json_out:
    json.dump({"bench": "fleet_load", "duration_s": duration, "run": run, "cores": ncpu, "recv_buf_size": buf,
               "rmem_max": rmem, "lcm_udpm": {"short_message_max": SHORT_MAX, "fragment_payload": FRAG_PAYLOAD},
               "processes": procs, "channels": loss, "signed_senders": senders, "udp": udp_rows}, open(json_out, "w"), indent=1)
    print(f"wrote {json_out}")
PY
exit 0
