// The web page's first frame in real time (tests/web/web_page.sh): headless Chromium on SwiftShader,
// driven over the DevTools protocol on 127.0.0.1; prints the page's performance.now() when it
// reported its first complete frame (web/index.html pvFirstFrame: navigation start to the first
// frame with every view drawn, wasm download and compile included). Chromium's --screenshot runs
// use virtual time, which stops the page's clocks while it computes: useless for timing.
// With --message, waits on after the first frame for the page's message box (web/index.html
// #message) and prints its text on a second line ("" when none came within 10 s).
// Usage: node --experimental-websocket first_frame.mjs URL [TIMEOUT_MS] [--message]
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';

const [url, timeoutArg, messageFlag] = process.argv.slice(2);
const timeout = Number(timeoutArg || 30000);
const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'polarview-chromium-'));
const chromium = spawn('chromium', ['--headless=new', '--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
  '--remote-debugging-address=127.0.0.1', '--remote-debugging-port=0', `--user-data-dir=${profile}`,
  '--window-size=1200,700', 'about:blank'], { stdio: ['ignore', 'ignore', 'pipe'] });
const finish = (code, text) => {
  if (text) (code ? console.error : console.log)(text);
  // The profile goes once the browser has exited (it writes to it until then).
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
setTimeout(() => finish(1, `first_frame: no first frame within ${timeout} ms`), timeout).unref();

// The browser's DevTools port, from its "DevTools listening on ws://127.0.0.1:PORT/..." line.
const port = await new Promise(resolve => {
  let text = '';
  chromium.stderr.on('data', chunk => {
    text += chunk;
    const match = text.match(/DevTools listening on ws:\/\/127\.0\.0\.1:(\d+)\//);
    if (match) resolve(match[1]);
  });
});
const targets = await (await fetch(`http://127.0.0.1:${port}/json/list`)).json();
const page = targets.find(t => t.type === 'page');
const socket = new WebSocket(page.webSocketDebuggerUrl);
await new Promise(resolve => socket.addEventListener('open', resolve));
let nextId = 0;
const pending = new Map();
socket.addEventListener('message', event => {
  const message = JSON.parse(event.data);
  if (pending.has(message.id)) { pending.get(message.id)(message.result); pending.delete(message.id); }
});
const send = (method, params = {}) => new Promise(resolve => {
  const id = ++nextId;
  pending.set(id, resolve);
  socket.send(JSON.stringify({ id, method, params }));
});

await send('Page.enable');
await send('Page.navigate', { url });
const evaluate = async expression => {
  const result = await send('Runtime.evaluate', { expression, returnByValue: true });
  return (result && result.result && result.result.value) || '';
};
const sleep = ms => new Promise(resolve => setTimeout(resolve, ms));
let firstFrame = '';
while (!firstFrame) {
  firstFrame = await evaluate("(document.getElementById('status') || {dataset: {}}).dataset.firstFrameMs || ''");
  if (!firstFrame) await sleep(50);
}
if (messageFlag !== '--message') finish(0, firstFrame);
let message = '';
for (let waited = 0; !message && waited < 10000; waited += 50) {
  message = await evaluate("document.getElementById('message').classList.contains('shown') ? document.getElementById('message').textContent : ''");
  if (!message) await sleep(50);
}
finish(0, `${firstFrame}\n${message}`);
