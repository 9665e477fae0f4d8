#!/usr/bin/env bash
# The web viewer (docs/web.md) in headless Chromium on SwiftShader, against the desktop:
#  1. builds build-web with web/build.sh (Ninja: a no-op when nothing changed, so never stale);
#     the wasm must stay within 5 MB;
#  2. serves a folder holding the page and a broken OBJ on 127.0.0.1 (python3 -m http.server);
#  3. screenshots the default model, C2PS | CC at level 3 with Gaussian curvature, and compares it
#     with `polarview render` of the same view (compare_images.py says how, and why not pixel-exact);
#  4. the first complete frame must come within 3 s of navigation (first_frame.mjs, real time);
#  5. ?model=broken.obj: the page says why on the page (and keeps drawing the default model);
#  6. a reader's walkthrough in one browser (walkthrough.mjs: pick, drop, file chooser, link,
#     Copy link, Screenshot (PNG), the address's parameters).
# Skipped (exit 77, ctest SKIP_RETURN_CODE) where emscripten, chromium or ImGui's sources are
# missing: bash third_party/install_deps.sh installs them.
# Usage: web_page.sh POLARVIEW ROOT (needs a display for `render`: the README runs ctest under xvfb-run)
set -euo pipefail
polarview="$1"
root="$2"
skip() { echo "web page test skipped: $1 (bash third_party/install_deps.sh installs it)"; exit 77; }
command -v emcmake >/dev/null || skip "emscripten not installed"
command -v chromium >/dev/null || skip "chromium not installed"
[ -f "$root/third_party/imgui-1.86/imgui.cpp" ] || skip "Dear ImGui's sources not at third_party/imgui-1.86"

work="$(mktemp -d)"
server=""
cleanup() {
  [ -n "$server" ] && kill "$server" 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT
# Chromium's profiles (first_frame.mjs, walkthrough.mjs: os.tmpdir()) go under $work too: a profile
# a helper process still wrote to when the browser exited goes with it.
export TMPDIR="$work"
seconds() { date +%s.%N; }

# --- 1. build (timed; the first build in a fresh checkout compiles the core, about a minute on 2 cores) ---
start=$(seconds)
bash "$root/web/build.sh" "$root/build-web" >"$work/build.log" 2>&1 || { cat "$work/build.log"; echo "FAIL: web/build.sh"; exit 1; }
echo "web/build.sh: $(awk "BEGIN { printf \"%.1f\", $(seconds) - $start }") s"
wasm_bytes=$(stat -c %s "$root/build-web/polarview.wasm")
echo "wasm: $wasm_bytes bytes"
[ "$wasm_bytes" -le $((5 * 1024 * 1024)) ] || { echo "FAIL: polarview.wasm is over 5 MB"; exit 1; }

# --- 2. serve the page and a broken OBJ, on 127.0.0.1 only, on a port the system picks ---
mkdir "$work/site"
for f in index.html polarview.js polarview.wasm; do ln -s "$root/build-web/$f" "$work/site/$f"; done
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n' >"$work/site/broken.obj"  # face index 9 of 3 vertices
(cd "$work/site" && exec python3 -u -m http.server --bind 127.0.0.1 0 >"$work/server.log" 2>&1) &
server=$!
port=""
for _ in $(seq 100); do
  port=$(sed -n 's/.*127\.0\.0\.1 port \([0-9]*\).*/\1/p' "$work/server.log" | head -1)
  [ -n "$port" ] && break
  sleep 0.1
done
[ -n "$port" ] || { cat "$work/server.log"; echo "FAIL: the web server did not start"; exit 1; }
base="http://127.0.0.1:$port/index.html"
chrome() {
  timeout 120 chromium --headless=new --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader \
    --virtual-time-budget=30000 --window-size=1200,700 "$@" 2>>"$work/chromium.log"
}

# --- 3. the view as a link, against the desktop's render of it ---
view="scheme=c2ps,cc&level=3&shade=gaussian"
"$polarview" render --scheme c2ps,cc --level 3 --shade gaussian --size 1200x700 -o "$work/desktop.png" >/dev/null
# Virtual time may end before a slow machine's first frame: up to three screenshots.
for try in 1 2 3; do
  chrome --screenshot="$work/web.png" "$base?$view&panels=0" >/dev/null
  echo -n "web vs desktop (try $try): "
  if /usr/bin/python3 "$root/tests/web/compare_images.py" "$work/web.png" "$work/desktop.png"; then break; fi
  if [ "$try" = 3 ]; then
    mkdir -p "$root/build-web/test-output" && cp "$work/web.png" "$work/desktop.png" "$root/build-web/test-output/"
    echo "FAIL: the page's view differs from the desktop's (both kept in build-web/test-output)"
    exit 1
  fi
done

# --- 4. the first frame, in real time ---
first_ms=$(node --no-warnings --experimental-websocket "$root/tests/web/first_frame.mjs" "$base?$view&panels=0" 30000)
echo "first frame: $first_ms ms after navigation"
[ "$first_ms" -le 3000 ] || { echo "FAIL: the first frame took over 3 s"; exit 1; }

# --- 5. a broken OBJ: a message on the page, the default model still drawn (its first frame came) ---
{ read -r broken_first_ms; read -r message; } < <(node --no-warnings --experimental-websocket \
  "$root/tests/web/first_frame.mjs" "$base?$view&model=broken.obj" 30000 --message)
echo "broken OBJ: first frame at $broken_first_ms ms, message \"$message\""
case "$message" in
  broken.obj*) ;;
  *) echo "FAIL: no message naming broken.obj on the page"; exit 1 ;;
esac

# --- 6. a reader's walkthrough (walkthrough.mjs): pick at the pole against `polarview pole`, a dropped
#     OBJ (default.obj x 1e20: same colours, range x 1e-40), Open OBJ..., a drag and its link reopened,
#     Copy link, Screenshot (PNG), the address's parameters and bad ones ---
awk '/^v /{printf "v %.17g %.17g %.17g\n", $2 * 1e20, $3 * 1e20, $4 * 1e20; next} {print}' \
  "$root/assets/default.obj" >"$work/default_x1e20.obj"
pole=$("$polarview" pole "$root/assets/default.obj" --json | /usr/bin/python3 -c 'import json, sys
p = json.load(sys.stdin)["poles"][0]
print(json.dumps({"position": p["limit"], "K": p["gaussian_curvature"], "H": p["mean_curvature"]}))')
start=$(seconds)
if ! node --no-warnings --experimental-websocket "$root/tests/web/walkthrough.mjs" "$base" "$work" "$root" "$pole"; then
  mkdir -p "$root/build-web/test-output" && cp "$work"/*.png "$root/build-web/test-output/" 2>/dev/null || true
  echo "FAIL: the walkthrough (its screenshots kept in build-web/test-output)"
  exit 1
fi
echo "walkthrough: $(awk "BEGIN { printf \"%.1f\", $(seconds) - $start }") s"
echo "web page: ok"
