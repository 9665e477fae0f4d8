// The web page as a reader uses it (tests/web/web_page.sh), in one headless Chromium on SwiftShader
// driven over the DevTools protocol on 127.0.0.1 (as first_frame.mjs): real mouse events on the
// canvas, the file chooser, a file dropped on the page, the download, the clipboard. The page's
// hidden #status element (web_main.cpp publishStatus) says where the pole markers and buttons are
// and what the panel shows (model, views, colour range, pick readout, error).
//  1. a click on the C2PS pole marker: the readout's position, K and H are the pole's
//     (`polarview pole`, passed in); a click off the surface says so;
//  2. a dropped OBJ, default.obj scaled by 1e20: colour range x 1e-40, the same pixels as the
//     unscaled model (curvature units, web_scene.h unit());
//  3. Open OBJ... (the file chooser) loads a model;
//  4. orbit by a drag; the address bar's link (and Copy link's clipboard) reopened shows the same
//     pixels;
//  5. Screenshot (PNG) downloads a PNG that is the page's canvas;
//  6. ?scheme=rts,bps&level=2&shade=mean is shown as written; bad values give a message on the
//     page and the defaults, not a blank page.
// Prints one line per check; exits 1 at the first failure (screenshots kept in WORK).
// Usage: node --experimental-websocket walkthrough.mjs BASE_URL WORK_DIR ROOT POLE_JSON
//   POLE_JSON: {"position":[x,y,z],"K":k,"H":h} of default.obj's pole under C2PS.
import { spawn, execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';

const [base, work, root, poleJson] = process.argv.slice(2);
const pole = JSON.parse(poleJson);
const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'polarview-chromium-'));
const downloads = path.join(work, 'downloads');
fs.mkdirSync(downloads, { recursive: true });
const chromium = spawn('chromium', ['--headless=new', '--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
  '--remote-debugging-address=127.0.0.1', '--remote-debugging-port=0', `--user-data-dir=${profile}`,
  '--window-size=1200,700', '--hide-scrollbars', 'about:blank'], { stdio: ['ignore', 'ignore', 'pipe'] });
const started = Date.now();
const finish = code => {
  chromium.once('exit', () => {
    // Chromium's helper processes may still write there after the browser's exit: a profile left
    // behind in the temporary directory is no test failure.
    try {
      fs.rmSync(profile, { recursive: true, force: true, maxRetries: 5 });
    } catch (error) {
      console.error(`note: ${profile} left behind (${error.code})`);
    }
    process.exit(code);
  });
  chromium.kill();
};
class Stop extends Error {}
const fail = text => { console.log(`FAIL: ${text}`); finish(1); throw new Stop(); };
process.on('uncaughtException', error => {
  if (error instanceof Stop) return;
  console.log(`FAIL: ${error.stack || error}`);
  finish(1);
});
const ok = text => console.log(`ok ${((Date.now() - started) / 1000).toFixed(1)} s: ${text}`);
setTimeout(() => fail('walkthrough: over 90 s'), 90000).unref();

const port = await new Promise(resolve => {
  let text = '';
  chromium.stderr.on('data', chunk => {
    text += chunk;
    const match = text.match(/DevTools listening on ws:\/\/127\.0\.0\.1:(\d+)\//);
    if (match) resolve(match[1]);
  });
});

// A DevTools connection: send(method, params) -> result; on(event, handler).
async function connect(url) {
  const socket = new WebSocket(url);
  await new Promise(resolve => socket.addEventListener('open', resolve));
  let nextId = 0;
  const pending = new Map(), handlers = new Map();
  socket.addEventListener('message', event => {
    const message = JSON.parse(event.data);
    if (pending.has(message.id)) {
      const { resolve, method } = pending.get(message.id);
      pending.delete(message.id);
      if (message.error) fail(`${method}: ${message.error.message}`);
      else resolve(message.result);
    } else if (message.method && handlers.has(message.method)) {
      handlers.get(message.method)(message.params);
    }
  });
  return {
    send: (method, params = {}) => new Promise(resolve => {
      const id = ++nextId;
      pending.set(id, { resolve, method });
      socket.send(JSON.stringify({ id, method, params }));
    }),
    on: (method, handler) => handlers.set(method, handler),
  };
}
const version = await (await fetch(`http://127.0.0.1:${port}/json/version`)).json();
const browser = await connect(version.webSocketDebuggerUrl);
const targets = await (await fetch(`http://127.0.0.1:${port}/json/list`)).json();
const page = await connect(targets.find(t => t.type === 'page').webSocketDebuggerUrl);

const sleep = ms => new Promise(resolve => setTimeout(resolve, ms));
const evaluate = async (expression, awaitPromise = false) => {
  const result = await page.send('Runtime.evaluate', { expression, returnByValue: true, awaitPromise });
  if (result.exceptionDetails) return { error: result.exceptionDetails.exception?.description || result.exceptionDetails.text };
  return result.result.value;
};
const status = async () => evaluate("Object.assign({}, document.getElementById('status').dataset)");
// Polls the page's status until test(status) holds (or fails after `ms`).
async function waitFor(what, test, ms = 15000) {
  for (let waited = 0; waited < ms; waited += 50) {
    const s = await status();
    if (s && test(s)) return s;
    await sleep(50);
  }
  fail(`${what}: not within ${ms} ms (status ${JSON.stringify(await status())})`);
}
// Two animation frames: what was just sent has been drawn.
const frames = () => evaluate('new Promise(r => requestAnimationFrame(() => requestAnimationFrame(r)))', true);
async function open(url) {
  await page.send('Page.navigate', { url });
  await sleep(100);
  return waitFor(`first frame of ${url}`, s => s.firstFrameMs && s.poles !== undefined && s.buttons !== undefined);
}
async function screenshot(name) {
  await frames();
  const { data } = await page.send('Page.captureScreenshot', { format: 'png' });
  const file = path.join(work, name);
  fs.writeFileSync(file, Buffer.from(data, 'base64'));
  return file;
}
// compare_pixels.py: the share of differing pixels in the box, at most `limit`.
function samePixels(what, a, b, box, limit) {
  try {
    const out = execFileSync('/usr/bin/python3', [path.join(root, 'tests/web/compare_pixels.py'), a, b, box.join(','), String(limit)]);
    ok(`${what}: ${out.toString().trim()}`);
  } catch (e) {
    fail(`${what}: ${(e.stdout || '').toString().trim()} (${path.basename(a)}, ${path.basename(b)} kept in ${work})`);
  }
}
const mouse = (type, x, y, button = 'none', buttons = 0) =>
  page.send('Input.dispatchMouseEvent', { type, x, y, button, buttons, clickCount: type === 'mouseMoved' ? 0 : 1 });
async function click(x, y) {
  await mouse('mouseMoved', x, y);
  await frames();  // ImGui sees the cursor there before the press (no drag)
  await mouse('mousePressed', x, y, 'left', 1);
  await mouse('mouseReleased', x, y, 'left', 0);
  await frames();
}
const centreOf = rect => [(rect[0] + rect[2]) / 2, (rect[1] + rect[3]) / 2];

await page.send('Page.enable');
await page.send('Runtime.enable');
await page.send('Emulation.setFocusEmulationEnabled', { enabled: true });
const origin = new URL(base).origin;
await browser.send('Browser.grantPermissions', { origin, permissions: ['clipboardReadWrite', 'clipboardSanitizedWrite'] });
await browser.send('Browser.setDownloadBehavior', { behavior: 'allow', downloadPath: downloads, eventsEnabled: true });

const panel = 330, colourBar = 86;  // web_main.cpp kPanelWidth, kColourBarStrip

// --- the default model, framed ---
const view = 'scheme=c2ps,cc&level=3&shade=gaussian';
let s = await open(`${base}?${view}`);
const framed = await screenshot('framed.png');
const range = s.range.split(' ').map(Number);
// The page's size (the window's, less what headless Chromium keeps for itself).
const [width, height] = await evaluate('[window.innerWidth, window.innerHeight]');
const views = [panel, 0, width, height - colourBar];  // the views, without the colour bar's tick labels

// --- 1. a click on the C2PS view's pole: the pick readout is the pole's ---
const marker = JSON.parse(s.poles).find(p => p[0] === 0);
if (!marker) fail(`no pole marker in the C2PS view (${s.poles})`);
await click(marker[1], marker[2]);
s = await waitFor('the pick readout', s => s.pick);
const numbers = text => (text || '').match(/-?\d+(\.\d+)?(e[-+]?\d+)?/gi)?.map(Number) || [];
const position = numbers(s.pick.match(/position \(([^)]*)\)/)?.[1]);
const K = Number(s.pick.match(/K (\S+)/)?.[1]), H = Number(s.pick.match(/H (\S+)/)?.[1]);
const far = Math.hypot(...position.map((x, i) => x - pole.position[i]));
// A pixel from the pole (radius / 150 at this zoom); K and H are continuous there (C2PS is C2).
if (!s.pick.startsWith('C2PS view:') || !(far < 0.02) || !(Math.abs(K - pole.K) < 0.02 * Math.abs(pole.K)) ||
    !(Math.abs(H - pole.H) < 0.02 * Math.abs(pole.H)))
  fail(`pick at the pole marker: ${JSON.stringify(s.pick)} against the pole ${poleJson}`);
ok(`pick at the pole: K ${K} H ${H}, ${far.toExponential(2)} from the pole (polarview pole: K ${pole.K} H ${pole.H})`);
await click(panel + 20, 60);  // the background, above the model
s = await waitFor('a pick off the surface', s => s.pick === 'no surface under the cursor');
ok('a click off the surface: "no surface under the cursor"');

// --- 2. a dropped OBJ: default.obj x 1e20 has the unscaled colours, its range x 1e-40 (float-sized
// curvature and clip coordinates at any scale) ---
const scaled = path.join(work, 'default_x1e20.obj');
const drag = type => page.send('Input.dispatchDragEvent', { type, x: 800, y: 350, data: { items: [], files: [scaled], dragOperationsMask: 1 } });
await drag('dragEnter');
await drag('dragOver');
await drag('drop');
s = await waitFor('the dropped default_x1e20.obj', s => s.model === 'default_x1e20.obj');
await frames();
s = await status();
const scaledRange = s.range.split(' ').map(Number);
if (!scaledRange.every((r, i) => Math.abs(r - 1e-40 * range[i]) <= 1e-8 * Math.abs(1e-40 * range[i])))
  fail(`dropped default x 1e20: colour range ${s.range}, expected 1e-40 x ${range.join(' ')}`);
ok(`dropped default_x1e20.obj: colour range ${s.range} (unscaled ${range.join(' ')})`);
samePixels('default x 1e20 has the unscaled model\'s colours', framed, await screenshot('dropped_x1e20.png'), views, 0.005);

// --- 3. Open OBJ...: the file chooser ---
await page.send('Page.setInterceptFileChooserDialog', { enabled: true });
const chooser = new Promise(resolve => page.on('Page.fileChooserOpened', resolve));
await click(...centreOf(JSON.parse(s.buttons).open));
const opened = await Promise.race([chooser, sleep(5000).then(() => null)]);
if (!opened) fail('Open OBJ...: no file chooser opened');
const cone = path.join(root, 'assets/cap6_cone.obj');
await page.send('DOM.setFileInputFiles', { files: [cone], backendNodeId: opened.backendNodeId });
s = await waitFor('Open OBJ... cap6_cone.obj', s => s.model === 'cap6_cone.obj' && s.firstFrameMs);
await frames();
s = await status();
if (s.error || !/^c2ps level \d+ \d+ triangles;cc level/.test(s.views)) fail(`after Open OBJ...: ${JSON.stringify(s)}`);
ok(`Open OBJ...: cap6_cone.obj shown (${s.views})`);
await screenshot('cone.png');

// --- 4. a drag turns the view; the address is a link to it; Copy link copies it ---
s = await open(`${base}?${view}`);
await mouse('mouseMoved', 900, 350);
await frames();
await mouse('mousePressed', 900, 350, 'left', 1);
for (let step = 1; step <= 3; ++step) {
  await mouse('mouseMoved', 900 + 20 * step, 350 + 8 * step, 'left', 1);
  await frames();
}
await mouse('mouseReleased', 960, 374, 'left', 0);
await mouse('mouseMoved', 1190, 690);  // off the views' middle (ImGui hover changes nothing there)
await frames();
const turned = await screenshot('turned.png');
const href = await evaluate('window.location.href');
if (!/[?&]camera=/.test(href) || !href.includes(view)) fail(`the address is no link to the view: ${href}`);
await click(...centreOf(JSON.parse(s.buttons).copyLink));
s = await waitFor('Copy link', s => s.note);
const clipboard = await evaluate('navigator.clipboard.readText()', true);
if (s.note !== 'link copied' || clipboard !== href) fail(`Copy link: note "${s.note}", clipboard ${JSON.stringify(clipboard)}, address ${href}`);
ok(`Copy link: the clipboard holds the address (${href.length} characters)`);
s = await open(href);
const reopened = await screenshot('reopened.png');
samePixels('the link reopened shows the turned view', turned, reopened, views, 0.002);
// The framed view is not it (the check can fail).
try {
  execFileSync('/usr/bin/python3', [path.join(root, 'tests/web/compare_pixels.py'), framed, reopened, views.join(','), '0.02']);
  fail('the turned view looks like the framed one: the drag did not turn it');
} catch (e) { if (e instanceof Stop) throw e; }

// --- 5. Screenshot (PNG): a download of the canvas ---
await click(...centreOf(JSON.parse(s.buttons).screenshot));
const pageShot = await screenshot('page.png');
const expected = 'polarview_c2ps_cc_level3_gaussian.png';
let downloaded = '';
for (let waited = 0; !downloaded && waited < 10000; waited += 100) {
  const names = fs.readdirSync(downloads).filter(name => name.endsWith('.png'));
  if (names.length) downloaded = names[0];
  else await sleep(100);
}
if (downloaded !== expected) fail(`Screenshot (PNG): downloaded ${JSON.stringify(downloaded)}, expected ${expected}`);
const png = fs.readFileSync(path.join(downloads, downloaded));
const pngSize = [png.readUInt32BE(16), png.readUInt32BE(20)];
if (png.toString('latin1', 1, 4) !== 'PNG' || pngSize[0] !== width || pngSize[1] !== height)
  fail(`Screenshot (PNG): not a ${width} x ${height} PNG (${pngSize})`);
samePixels(`Screenshot (PNG) ${downloaded} (${png.length} bytes) is the page`, path.join(downloads, downloaded), pageShot,
  [0, 0, width, height], 0.002);

// --- 6. the address's parameters, and bad ones ---
s = await open(`${base}?scheme=rts,bps&level=2&shade=mean`);
await frames();
s = await status();
const link = await evaluate('window.location.search');
const messageShown = () => evaluate("document.getElementById('message').classList.contains('shown') ? document.getElementById('message').textContent : ''");
if (!/^rts level 2 \d+ triangles;bps level 2 \d+ triangles$/.test(s.views) || !link.startsWith('?scheme=rts,bps&level=2&shade=mean&camera=') ||
    s.error || await messageShown())
  fail(`?scheme=rts,bps&level=2&shade=mean: views "${s.views}", link ${link}, error "${s.error}"`);
ok(`?scheme=rts,bps&level=2&shade=mean: ${s.views}`);
await screenshot('rts_bps_mean.png');
s = await open(`${base}?scheme=rts,foo&level=abc&shade=gauss&camera=%7Bnope`);
await frames();
s = await status();
const message = await messageShown();
for (const part of ["scheme 'foo' unknown", "level 'abc'", "shade 'gauss' unknown", 'camera'])
  if (!message.includes(part) || !s.error.includes(part)) fail(`bad parameters: message "${message}", panel "${s.error}" lack "${part}"`);
if (!/^rts level 3 \d+ triangles$/.test(s.views)) fail(`bad parameters: views "${s.views}" (expected rts at the default level)`);
const bad = await screenshot('bad_parameters.png');
const surface = JSON.parse(execFileSync('/usr/bin/python3', [path.join(root, 'tests/web/compare_pixels.py'), bad, bad, views.join(','), '1'])).surface_share;
if (!(surface > 0.05)) fail(`bad parameters: the page draws no surface (${surface} of the views saturated)`);
ok(`bad parameters: "${message}"; rts level 3 drawn (${surface} of the views)`);
finish(0);
