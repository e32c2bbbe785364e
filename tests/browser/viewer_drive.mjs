// Drives the viewer page in headless Chromium through the DevTools protocol over a pipe
// (no network port, no npm packages), as a person would: waits for it to load, watches it
// play, presses space, clicks the timeline, drags, wheels and double-clicks the 3D view,
// and collects every console message and exception.
//
//   node viewer_drive.mjs CHROMIUM PAGE_URL PROFILE_DIR SCREENSHOT.png
//
// Prints one JSON object with the observations (see `result` below).
import { spawn } from "node:child_process";
import fs from "node:fs";

const [chromium, url, profile, shot, throttle] = process.argv.slice(2);  // throttle: CPU slowdown factor (a slow machine)
const proc = spawn(chromium, [
  "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
  "--disable-background-networking", "--disable-component-update", "--disable-sync", "--hide-scrollbars",
  "--mute-audio", `--user-data-dir=${profile}`, "--remote-debugging-pipe", "about:blank",
], { stdio: ["ignore", "ignore", "pipe", "pipe", "pipe"] });
let stderr = "";
proc.stderr.on("data", (d) => { stderr += d; });
const killer = setTimeout(() => { fail("timed out"); }, 60000);

const toBrowser = proc.stdio[3], fromBrowser = proc.stdio[4];
let nextId = 1, buffer = "";
const pending = new Map(), events = [];
fromBrowser.on("data", (chunk) => {
  buffer += chunk.toString("utf8");
  let end;
  while ((end = buffer.indexOf("\0")) >= 0) {
    const msg = JSON.parse(buffer.slice(0, end));
    buffer = buffer.slice(end + 1);
    if (msg.id && pending.has(msg.id)) {
      const { resolve, reject } = pending.get(msg.id);
      pending.delete(msg.id);
      if (msg.error) reject(new Error(JSON.stringify(msg.error))); else resolve(msg.result);
    } else if (msg.method) {
      events.push(msg);
    }
  }
});
function send(method, params = {}, sessionId) {
  const id = nextId++;
  const msg = { id, method, params };
  if (sessionId) msg.sessionId = sessionId;
  toBrowser.write(JSON.stringify(msg) + "\0");
  return new Promise((resolve, reject) => pending.set(id, { resolve, reject }));
}
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
function fail(why) {
  process.stdout.write(JSON.stringify({ error: String(why), stderr: stderr.slice(-3000) }));
  try { proc.kill("SIGKILL"); } catch (e) { /* gone */ }
  process.exit(0);
}

try {
  const { targetId } = await send("Target.createTarget", { url: "about:blank" });
  const { sessionId: s } = await send("Target.attachToTarget", { targetId, flatten: true });
  const cmd = (m, p) => send(m, p, s);
  const js = async (expression) => {
    const r = await cmd("Runtime.evaluate", { expression, returnByValue: true, awaitPromise: true });
    if (r.exceptionDetails) throw new Error("evaluate: " + JSON.stringify(r.exceptionDetails));
    return r.result.value;
  };
  await cmd("Runtime.enable"); await cmd("Log.enable"); await cmd("Page.enable");
  await cmd("Emulation.setDeviceMetricsOverride", { width: 1200, height: 800, deviceScaleFactor: 1, mobile: false });
  if (Number(throttle) > 1) await cmd("Emulation.setCPUThrottlingRate", { rate: Number(throttle) });
  await cmd("Page.navigate", { url });
  let ready = null;
  for (let i = 0; i < 100 && ready !== "1" && ready !== "error"; i++) {
    await sleep(50);
    ready = await js("document.body && document.body.dataset.ready");
  }
  // now: the page's own clock (ms) at the step that set its time: how fast it plays is measured on it, not on
// this script's sleeps, which a loaded machine stretches (a CDP round trip alone can take longer than a sleep)
const snap = () => js("(() => { const a = window.__t2a; return { frame: a.frame, time: a.time, playing: a.playing, speed: a.speed, follow: a.follow, camera: a.camera, duration: a.duration, now: a.clock }; })()");
  const result = { ready };
  result.start = await snap();
  await sleep(1000);
  result.afterPlaying = await snap();

  const key = async (k, code, vk) => {
    await cmd("Input.dispatchKeyEvent", { type: "keyDown", key: k, code, windowsVirtualKeyCode: vk, text: k === " " ? " " : undefined });
    await cmd("Input.dispatchKeyEvent", { type: "keyUp", key: k, code, windowsVirtualKeyCode: vk });
  };
  await key(" ", "Space", 32);
  result.paused = await snap();
  await sleep(300);
  result.stillPaused = await snap();
  await key("ArrowRight", "ArrowRight", 39);
  result.stepped = await snap();

  // click the middle of the timeline
  const half = result.start.duration / 2;
  const p = await js(`window.__t2a.timelinePoint(${half})`);
  const mouse = (type, x, y, extra = {}) => cmd("Input.dispatchMouseEvent", { type, x, y, button: "left", clickCount: 1, ...extra });
  await mouse("mousePressed", p.x, p.y, { buttons: 1 });
  await mouse("mouseReleased", p.x, p.y);
  await sleep(150);
  result.seeked = await snap();
  result.seekTarget = half;

  // drag in the 3D view: orbit
  const cx = 600, cy = 300;
  await mouse("mousePressed", cx, cy, { buttons: 1 });
  for (let i = 1; i <= 5; i++) await mouse("mouseMoved", cx + 30 * i, cy + 8 * i, { buttons: 1 });
  await mouse("mouseReleased", cx + 150, cy + 40);
  await sleep(100);
  result.dragged = await snap();
  await cmd("Input.dispatchMouseEvent", { type: "mouseWheel", x: cx, y: cy, deltaX: 0, deltaY: 400 });
  await sleep(150);
  result.zoomed = await snap();
  await mouse("mousePressed", cx, cy, { clickCount: 1, buttons: 1 });
  await mouse("mouseReleased", cx, cy, { clickCount: 1 });
  await mouse("mousePressed", cx, cy, { clickCount: 2, buttons: 1 });
  await mouse("mouseReleased", cx, cy, { clickCount: 2 });
  await sleep(150);
  result.reset = await snap();

  await js(`(() => { const s = document.getElementById("speed"); s.value = "2"; s.dispatchEvent(new Event("change")); })()`);
  await js("window.__t2a.seek(0)");  // from the start: a second at 2x must not loop back
  await key(" ", "Space", 32);
  const before = await snap();
  await sleep(1000);
  result.doubleSpeed = { ...(await snap()), from: before.time, fromNow: before.now };

  const png = await cmd("Page.captureScreenshot", { format: "png" });
  fs.writeFileSync(shot, Buffer.from(png.data, "base64"));
  result.console = events.filter((e) => e.sessionId === s && (e.method === "Runtime.consoleAPICalled" || e.method === "Runtime.exceptionThrown" || e.method === "Log.entryAdded"))
    .map((e) => e.method + ": " + JSON.stringify(e.params).slice(0, 400));
  result.pageErrors = await js("window.__t2aErrors");
  clearTimeout(killer);
  await send("Browser.close").catch(() => {});
  process.stdout.write(JSON.stringify(result));
  setTimeout(() => { try { proc.kill("SIGKILL"); } catch (e) { /* gone */ } process.exit(0); }, 500);
} catch (e) {
  fail(e && e.stack ? e.stack : e);
}
