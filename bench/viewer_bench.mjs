// The operator's view under the running fleet (bench/viewer_bench.sh): headless chromium
// (Debian's, driven by npm playwright-core) keeps the page open for --duration seconds,
// following the vehicle at the default zoom; every second it reads the page's own counters
// (animation frames, redraws, bytes and messages received over the WebSocket). Prints one
// JSON object: per-second samples and their medians.
//   node bench/viewer_bench.mjs --url URL --duration S [--screenshot FILE]
import { createRequire } from "node:module";
import { mkdtempSync, rmSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";

const here = dirname(fileURLToPath(import.meta.url));
const { chromium } = createRequire(join(here, "..", "tests", "js", "package.json"))("playwright-core");
const args = Object.fromEntries(process.argv.slice(2).reduce((acc, a, i, all) => {
  if (a.startsWith("--")) acc.push([a.slice(2), all[i + 1]]);
  return acc;
}, []));
const duration = Number(args.duration || 30);
const userDataDir = mkdtempSync(join(tmpdir(), "minenav-chromium-"));
const context = await chromium.launchPersistentContext(userDataDir, {
  executablePath: "/usr/bin/chromium", headless: true, viewport: { width: 1280, height: 800 },
  args: ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync"],
});
const page = context.pages()[0] || await context.newPage();
const median = (v) => { const s = [...v].sort((a, b) => a - b); return s.length ? s[Math.floor(s.length / 2)] : null; };
try {
  await page.goto(args.url);
  await page.waitForFunction(() => window.minenavViewer && window.minenavViewer.state.connected, null, { timeout: 10000 });
  await page.waitForTimeout(3000);  // the latched state (map, walls) arrives first: not counted
  const samples = [];
  for (let i = 0; i < duration; i++) {
    await page.waitForTimeout(1000);
    samples.push(await page.evaluate(() => {
      const s = window.minenavViewer.stats;
      return { fps: s.fps, redraws: s.redrawsPerS, bytes: s.bytesPerS, messages: s.messagesPerS };
    }));
  }
  const state = await page.evaluate(() => {
    const s = window.minenavViewer.state;
    return { contours: s.map ? s.map.contours.length : 0, map_version: s.map ? s.map.version : null,
             track_points: s.track.length, bridge: s.bridge };
  });
  if (args.screenshot) writeFileSync(args.screenshot, await page.screenshot());
  console.log(JSON.stringify({
    seconds: samples.length,
    fps_median: median(samples.map((s) => s.fps)), fps_min: Math.min(...samples.map((s) => s.fps)),
    redraws_median: median(samples.map((s) => s.redraws)),
    page_bytes_per_s_median: median(samples.map((s) => s.bytes)),
    page_bytes_per_s_max: Math.max(...samples.map((s) => s.bytes)),
    messages_per_s_median: median(samples.map((s) => s.messages)),
    ...state, samples,
  }));
} finally {
  await context.close();
  rmSync(userDataDir, { recursive: true, force: true });
}
