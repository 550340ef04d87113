// The operator's view in Debian's chromium, driven by playwright-core (viewer/browser_test.sh
// runs it inside a private network namespace, with viewer_bridge listening and the known log
// ready). Checks, each against a reference the page does not make:
//   - the contour map is drawn on the true walls (world.json) where this script's own view
//     transform puts them, read from a screenshot; the same check with the walls moved by
//     (2.3 m, 1.7 m) must fail (the check can fail);
//   - the view follows the vehicle: the estimated pose stays at the canvas centre while the
//     log plays, and the screenshot shows the vehicle's colour there;
//   - the mission tree marks the current station, the fleet table lists the processes;
//   - pressing Pause gets the bridge's "command sent" status (browser_test.sh then finds the
//     PAUSE on the bus).
//
//   node browser_test.mjs --url URL --world world.json --log known.lcm --screenshot OUT.png
//                         [--replay-url URL --stations stations.csv]
import { spawn } from "node:child_process";
import { createRequire } from "node:module";
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";

const here = dirname(fileURLToPath(import.meta.url));
const require = createRequire(join(here, "..", "tests", "js", "package.json"));
const { chromium } = require("playwright-core");

const args = Object.fromEntries(process.argv.slice(2).reduce((acc, a, i, all) => {
  if (a.startsWith("--")) acc.push([a.slice(2), all[i + 1]]);
  return acc;
}, []));
const failures = [];
function check(ok, what) {
  console.log(`${ok ? "ok  " : "FAIL"} ${what}`);
  if (!ok) failures.push(what);
}

const world = JSON.parse(readFileSync(args.world, "utf8")).segments;
const userDataDir = mkdtempSync(join(tmpdir(), "minenav-chromium-"));
const context = await chromium.launchPersistentContext(userDataDir, {
  executablePath: "/usr/bin/chromium",
  headless: true,
  viewport: { width: 1280, height: 800 },
  args: ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync"],
});
const page = context.pages()[0] || await context.newPage();
const errors = [];
page.on("pageerror", (e) => errors.push(String(e)));
page.on("console", (m) => { if (m.type() === "error") errors.push(m.text()); });

try {
  await page.goto(args.url);
  await page.waitForFunction(() => window.minenavViewer && window.minenavViewer.state.connected, null, { timeout: 10000 });
  check(true, "the page loaded and connected (foxglove.websocket.v1)");
  await page.waitForFunction(() => !document.querySelector('button[data-cmd="PAUSE"]').disabled, null, { timeout: 5000 });

  // Play the known log; while it plays the view must follow the vehicle.
  const player = spawn("lcm-logplayer", [args.log], { stdio: "inherit" });
  const played = new Promise((resolve) => player.on("exit", resolve));
  const followed = [];
  for (let i = 0; i < 40; i++) {
    const s = await page.evaluate(async () => {
      const v = window.minenavViewer;
      const pose = v.state.pose;
      if (!pose) return null;
      // After two frames the page has drawn this pose (unless a newer one came meanwhile).
      await new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)));
      if (v.state.pose !== pose) return null;
      const [sx, sy] = v.worldToScreen(v.state.pose.pose.x, v.state.pose.pose.y);
      const c = document.getElementById("map");
      return { x: v.state.pose.pose.x, y: v.state.pose.pose.y, sx, sy, w: c.clientWidth, h: c.clientHeight };
    });
    if (s && !followed.some((f) => f.x === s.x && f.y === s.y)) followed.push(s);
    if (player.exitCode !== null && followed.length >= 3) break;
    await page.waitForTimeout(100);
  }
  const code = await played;
  check(code === 0, `lcm-logplayer played the known log (exit ${code})`);
  check(followed.length >= 3, `${followed.length} different poses seen while following`);
  check(followed.every((f) => Math.abs(f.sx - f.w / 2) < 1 && Math.abs(f.sy - f.h / 2) < 1),
        "each pose was at the canvas centre (follow)");
  await page.waitForFunction(() => window.minenavViewer.state.map && window.minenavViewer.state.map.version === 2,
                             null, { timeout: 5000 });

  // The canvas's screenshot, decoded in the page by the browser's own PNG decoder and kept as
  // window.__shot (an ImageData) for the checks that run there.
  async function screenshotPixels() {
    const png = await page.locator("#map").screenshot();
    await page.evaluate(async (url) => {
      const img = new Image();
      img.src = url;
      await img.decode();
      const c = document.createElement("canvas");
      c.width = img.width; c.height = img.height;
      const g = c.getContext("2d");
      g.drawImage(img, 0, 0);
      window.__shot = g.getImageData(0, 0, c.width, c.height);
    }, "data:image/png;base64," + png.toString("base64"));
  }
  async function mapCheck(dx, dy, view) {
    await screenshotPixels();
    const box = await page.locator("#map").boundingBox();
    // This script's own transform (x right, y up, the view's centre at the canvas centre).
    const samples = [];
    for (const [x1, y1, x2, y2] of world) {
      const n = Math.max(1, Math.ceil(Math.hypot(x2 - x1, y2 - y1) / 0.05));
      for (let i = 0; i <= n; i++) {
        const x = x1 + ((x2 - x1) * i) / n + dx, y = y1 + ((y2 - y1) * i) / n + dy;
        samples.push([box.width / 2 + (x - view.cx) * view.scale, box.height / 2 - (y - view.cy) * view.scale]);
      }
    }
    return page.evaluate((samples) => {
      const { data, width, height } = window.__shot;
      const blue = (x, y) => {
        if (x < 0 || y < 0 || x >= width || y >= height) return false;
        const i = 4 * (y * width + x);
        return data[i + 2] > 150 && data[i] < 120 && data[i + 1] < 160;  // #1f5fbf and its antialiasing
      };
      const near = new Uint8Array(width * height);
      let hits = 0, inside = 0;
      for (const [sx, sy] of samples) {
        const x = Math.round(sx), y = Math.round(sy);
        if (x < 3 || y < 3 || x >= width - 3 || y >= height - 3) continue;
        inside++;
        let hit = false;
        for (let oy = -3; oy <= 3; oy++) for (let ox = -3; ox <= 3; ox++) {
          near[(y + oy) * width + x + ox] = 1;
          if (Math.abs(ox) <= 2 && Math.abs(oy) <= 2 && blue(x + ox, y + oy)) hit = true;
        }
        if (hit) hits++;
      }
      let bluePixels = 0, stray = 0;
      for (let y = 0; y < height; y++) for (let x = 0; x < width; x++) {
        if (!blue(x, y)) continue;
        bluePixels++;
        if (!near[y * width + x]) stray++;
      }
      return { inside, hits, bluePixels, stray, width, height };
    }, samples);
  }

  // A fixed view on the whole world, walls and scan hidden: only the contour map is blue.
  const xs = world.flatMap((s) => [s[0], s[2]]), ys = world.flatMap((s) => [s[1], s[3]]);
  const box = await page.locator("#map").boundingBox();
  const view = { cx: (Math.min(...xs) + Math.max(...xs)) / 2, cy: (Math.min(...ys) + Math.max(...ys)) / 2 };
  view.scale = 0.9 * Math.min(box.width / (Math.max(...xs) - Math.min(...xs)), box.height / (Math.max(...ys) - Math.min(...ys)));
  await page.evaluate((view) => {
    const v = window.minenavViewer;
    document.getElementById("follow").checked = false;
    document.getElementById("show_walls").checked = false;
    document.getElementById("show_scan").checked = false;
    Object.assign(v.view, { follow: false, cx: view.cx, cy: view.cy, scale: view.scale });
    v.redraw();
  }, view);
  await page.waitForTimeout(200);
  const onWalls = await mapCheck(0, 0, view);
  const shifted = await mapCheck(2.3, 1.7, view);
  console.log(`     map on the walls: ${onWalls.hits}/${onWalls.inside} wall samples blue within 2 px; ` +
              `${onWalls.stray}/${onWalls.bluePixels} blue pixels farther than 3 px from a wall; walls moved (2.3 m, 1.7 m): ` +
              `${shifted.hits}/${shifted.inside}`);
  check(onWalls.inside > 1000 && onWalls.hits >= 0.95 * onWalls.inside, "the contour map is drawn on the true walls (>= 95 % of wall samples)");
  check(onWalls.bluePixels > 2000 && onWalls.stray <= 0.02 * onWalls.bluePixels, "and nowhere else (<= 2 % of map pixels off the walls)");
  check(shifted.hits < 0.3 * shifted.inside, "the check fails for walls moved by (2.3 m, 1.7 m) (< 30 %)");

  // Follow again: the vehicle's colour at the centre of the screenshot.
  await page.evaluate(() => {
    const v = window.minenavViewer;
    document.getElementById("follow").checked = true;
    document.getElementById("show_walls").checked = true;
    document.getElementById("show_scan").checked = true;
    Object.assign(v.view, { follow: true, scale: 40 });
    v.redraw();
  });
  await page.waitForTimeout(200);
  await screenshotPixels();
  const centre = await page.evaluate(() => {
    const shot = window.__shot;
    // Two points inside the vehicle's polygon, behind its reference point on either side
    // (clear of the heading line, the 2-sigma ellipse and the true pose's outline).
    const v = window.minenavViewer;
    const p = v.state.pose.pose;
    const colours = [0.35, -0.35].map((lateral) => {
      const x = p.x - 0.6 * Math.cos(p.theta) - lateral * Math.sin(p.theta);
      const y = p.y - 0.6 * Math.sin(p.theta) + lateral * Math.cos(p.theta);
      const [px, py] = v.worldToScreen(x, y);
      const i = 4 * (Math.round(py) * shot.width + Math.round(px));
      return Array.from(shot.data.slice(i, i + 3));
    });
    const [sx, sy] = v.worldToScreen(p.x, p.y);
    return { colours, sx, sy, w: shot.width, h: shot.height };
  });
  const vehicleColour = ([r, g, b]) => r > 200 && g > 150 && g < 225 && b < 190 && r - b > 50;
  check(Math.abs(centre.sx - centre.w / 2) < 1 && Math.abs(centre.sy - centre.h / 2) < 1, "the last pose is at the centre");
  check(centre.colours.some(vehicleColour),
        `the vehicle's fill colour inside its polygon at the centre (rgb ${JSON.stringify(centre.colours)})`);

  // Panels.
  const panels = await page.evaluate(() => ({
    fleet: document.querySelector("#fleet tbody").innerText,
    current: (document.querySelector("#tree .current") || {}).innerText || "",
    vehicle: document.getElementById("vehicle").innerText,
    mission: document.getElementById("mission").innerText,
  }));
  check(/contour_mapper/.test(panels.fleet) && /path_tracker/.test(panels.fleet) && /viewer_bridge/.test(panels.fleet),
        "the fleet table lists contour_mapper, path_tracker and viewer_bridge");
  check(/scan station 5/.test(panels.current), `the mission tree marks the current subtask ("${panels.current.trim()}")`);
  check(/ m, y .* m, θ .*°/.test(panels.vehicle) && /true pose off by 0\.36\d m/.test(panels.vehicle),
        `the vehicle panel has units and the known offset from the true pose (${panels.vehicle.split("\n").pop()})`);

  // The operator's Pause.
  await page.click('button[data-cmd="PAUSE"]');
  await page.waitForFunction(() => /seq 1/.test(document.getElementById("status").textContent), null, { timeout: 5000 });
  check(true, "Pause: the bridge answered 'command sent ... (seq 1)'");

  await page.waitForTimeout(2100);
  const stats = await page.evaluate(() => ({ ...window.minenavViewer.stats }));
  console.log(`     browser: ${stats.fps} frames/s, ${stats.redrawsPerS} redraws/s, ${stats.bytesPerS} B/s received (idle bus)`);
  check(stats.fps >= 10, "the page keeps animating (>= 10 frames/s headless)");
  check(errors.length === 0, `no errors in the page's console (${errors.join("; ")})`);
  if (args.screenshot) writeFileSync(args.screenshot, await page.screenshot());

  // The log read directly by the bridge (--replay) with the time slider: pause, seek to 1.0 s
  // (after the third station at 0.8 s, before the map's second version at 1.2 s).
  if (args["replay-url"]) {
    const stations = readFileSync(args.stations, "utf8").trim().split("\n").slice(1).map((l) => l.split(",").map(Number));
    await page.goto(args["replay-url"]);
    await page.waitForFunction(() => window.minenavViewer.state.replay && !document.getElementById("replay").hidden,
                               null, { timeout: 10000 });
    check(true, "replay: the time slider is shown");
    // Pause with the button unless the replay already ran to the end (where it pauses).
    if (!(await page.evaluate(() => window.minenavViewer.state.replay.paused))) {
      await page.click("#replay_play");
      await page.waitForFunction(() => window.minenavViewer.state.replay.paused, null, { timeout: 5000 });
    }
    const generation = await page.evaluate(() => window.minenavViewer.state.replay.generation);
    await page.locator("#replay_slider").fill("1");
    await page.waitForFunction((g) => {
      const s = window.minenavViewer.state;
      return s.replay.generation > g && s.pose && s.map && s.mission;
    }, generation, { timeout: 5000 });
    await page.waitForTimeout(300);
    const r = await page.evaluate(() => {
      const s = window.minenavViewer.state;
      return { time: s.replay.time_s, x: s.pose.pose.x, y: s.pose.pose.y, track: s.track.length, version: s.map.version,
               current: document.querySelector("#tree .current").innerText };
    });
    const [sx, sy] = stations[2];
    check(Math.abs(r.time - 1.0) < 1e-6, `replay: at ${r.time} s after the seek`);
    check(Math.abs(r.x - (sx + 0.3)) < 1e-6 && Math.abs(r.y - (sy - 0.2)) < 1e-6,
          `replay: the pose of station 2 (${r.x}, ${r.y}), the track of stations 0-2 (${r.track} points)`);
    check(r.track === 3, "replay: the driven track is rebuilt from the log (3 poses)");
    check(r.version === 1 && /scan station 2/.test(r.current), `replay: map version ${r.version}, current subtask "${r.current.trim()}"`);
  }
} catch (e) {
  check(false, `exception: ${e && e.stack ? e.stack : e}`);
} finally {
  await context.close();
  rmSync(userDataDir, { recursive: true, force: true });
}
if (failures.length) {
  console.log(`browser_test.mjs: ${failures.length} check(s) FAILED`);
  process.exit(1);
}
console.log("browser_test.mjs: all checks passed");
