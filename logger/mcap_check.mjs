// Reads log_tool export-mcap's file with an independent MCAP reader (npm @mcap/core, the one
// Foxglove's tools use), both ways: indexed (summary, chunk and message indexes) and
// streaming (every record in order), and checks it against `log_tool info --json` of the
// LCM log it came from (which reads the log with its own strict parser) and against what the
// known log was made of (viewer_test_log: POSE = SIM_TRUTH + (0.3 m, -0.2 m, 0.02 rad)).
//
//   node mcap_check.mjs OUT.mcap INFO.json
import { createRequire } from "node:module";
import { readFileSync } from "node:fs";
import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";

const here = dirname(fileURLToPath(import.meta.url));
const { McapIndexedReader, McapStreamReader } = await import(
  createRequire(join(here, "..", "tests", "js", "package.json")).resolve("@mcap/core"));

const [mcapPath, infoPath] = process.argv.slice(2);
const bytes = readFileSync(mcapPath);
const info = JSON.parse(readFileSync(infoPath, "utf8"));
const failures = [];
const check = (ok, what) => { console.log(`${ok ? "ok  " : "FAIL"} ${what}`); if (!ok) failures.push(what); };

// Indexed.
const readable = {
  size: async () => BigInt(bytes.length),
  read: async (offset, size) => new Uint8Array(bytes.buffer, bytes.byteOffset + Number(offset), Number(size)),
};
const reader = await McapIndexedReader.Initialize({ readable });
const topicOf = (id) => reader.channelsById.get(id).topic;
const byTopic = new Map();
let previous = -1n, ordered = true;
for await (const m of reader.readMessages({ validateCrcs: true })) {
  const topic = topicOf(m.channelId);
  if (!byTopic.has(topic)) byTopic.set(topic, []);
  byTopic.get(topic).push({ logTime: m.logTime, publishTime: m.publishTime, json: JSON.parse(new TextDecoder().decode(m.data)) });
  if (m.logTime < previous) ordered = false;
  previous = m.logTime;
}
check(ordered, "indexed reader: messages in log-time order");
check(reader.chunkIndexes.length >= Number(process.env.MCAP_MIN_CHUNKS || 1), `${reader.chunkIndexes.length} chunks indexed`);
check(reader.statistics && Number(reader.statistics.messageCount) === [...byTopic.values()].reduce((n, l) => n + l.length, 0),
      `statistics count ${reader.statistics && reader.statistics.messageCount} = messages read`);
for (const [id, ch] of reader.channelsById) {
  const schema = reader.schemasById.get(ch.schemaId);
  check(ch.messageEncoding === "json" && schema.encoding === "jsonschema" && JSON.parse(new TextDecoder().decode(schema.data)),
        `${ch.topic}: json with a parseable jsonschema (${schema.name})`);
}

// Every LCM channel with its count and its times (info.json: the log's own reading).
for (const c of info.channels) {
  const got = byTopic.get(c.channel) || [];
  check(got.length === c.count, `${c.channel}: ${got.length} messages, the log has ${c.count}`);
  if (got.length && c.first_utime !== undefined && c.first_utime !== null)
    check(Number(got[0].publishTime / 1000n) === c.first_utime, `${c.channel}: first publish time = first utime ${c.first_utime}`);
}

// Content against the construction of the known log.
const truth = new Map((byTopic.get("SIM_TRUTH") || []).map((m) => [m.json.utime, m.json.pose]));
const poses = byTopic.get("POSE") || [];
check(poses.length > 0 && poses.every((m) => {
  const t = truth.get(m.json.utime);
  return t && Math.abs(m.json.pose.x - t.x - 0.3) < 1e-9 && Math.abs(m.json.pose.y - t.y + 0.2) < 1e-9 &&
         Math.abs(m.json.pose.theta - t.theta - 0.02) < 1e-9;
}), "POSE = SIM_TRUTH + (0.3, -0.2, 0.02) for every scan");
const fox = byTopic.get("/foxglove/POSE") || [];
check(fox.length === poses.length && fox.every((m, i) => {
  const q = m.json.pose.orientation, p = poses[i].json.pose;
  const yaw = 2 * Math.atan2(q.z, q.w);
  return m.json.frame_id === "map" && Math.abs(Math.hypot(q.x, q.y, q.z, q.w) - 1) < 1e-12 &&
         Math.abs(Math.atan2(Math.sin(yaw - p.theta), Math.cos(yaw - p.theta))) < 1e-9 &&
         m.json.pose.position.x === p.x && m.json.timestamp.sec * 1e6 + m.json.timestamp.nsec / 1e3 === poses[i].json.utime;
}), "/foxglove/POSE: foxglove.PoseInFrame with the pose's position, yaw and time");
const scans = byTopic.get("LADAR_SCAN") || [], foxScans = byTopic.get("/foxglove/LADAR_SCAN") || [];
check(scans.length > 0 && scans.every((m) => m.json.ranges.length === m.json.num_ranges), "LADAR_SCAN: every range");
check(foxScans.length === scans.length && foxScans.every((m, i) => m.json.ranges.length === scans[i].json.num_ranges &&
      Math.abs(m.json.end_angle - m.json.start_angle - (scans[i].json.num_ranges - 1) * scans[i].json.angle_step) < 1e-6),
      "/foxglove/LADAR_SCAN: foxglove.LaserScan with every range and the angular span");
const maps = byTopic.get("CONTOUR_MAP") || [], walls = byTopic.get("SIM_WORLD") || [];
check(maps.length === 2 && walls.length === 1 && maps.every((m) => m.json.contours.length === walls[0].json.segments.length),
      `CONTOUR_MAP inflated: ${maps.length ? maps[0].json.contours.length : 0} contours, one per wall`);
const scene = byTopic.get("/foxglove/CONTOUR_MAP") || [];
check(scene.length === 2 && scene[0].json.entities[0].lines.length === maps[0].json.contours.length,
      "/foxglove/CONTOUR_MAP: foxglove.SceneUpdate, a line strip per contour");

// Streaming: the same messages, record by record.
const stream = new McapStreamReader({ validateCrcs: true });
stream.append(new Uint8Array(bytes.buffer, bytes.byteOffset, bytes.length));
let streamed = 0, footer = false;
for (let r; (r = stream.nextRecord()); ) {
  if (r.type === "Message") streamed++;
  if (r.type === "Footer") footer = true;
}
check(stream.done() && footer && streamed === Number(reader.statistics.messageCount),
      `stream reader: ${streamed} messages, to the footer`);

if (failures.length) {
  console.log(`mcap_check.mjs: ${failures.length} check(s) FAILED`);
  process.exit(1);
}
console.log("mcap_check.mjs: all checks passed");
