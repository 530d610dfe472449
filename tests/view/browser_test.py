#!/usr/bin/env python3
"""The viewer page in a real browser (ctest view.browser; docs/viewer.md).

    browser_test.py MO2D SCENE OUT_DIR [--every K] [--max-frames N] [-- RUN SETTINGS...]

Writes the page of SCENE (`mo2d view`) and the Cairo frames of the same run (`mo2d render --frames
--every K`; the run settings after `--`, e.g. --duration 10, given to both), loads the page in headless Chromium driven over the DevTools protocol
(--remote-debugging-pipe: Debian's python3 only, no package), and fails on:
  - any console error, uncaught exception or log error, and any request that is not a file:
    or data: URL (the page must be self-contained);
  - a page without the script API, or whose first frame came later than 2 s after navigation;
  - a joint pin (revolute or slot) that is not drawn where the page says it is: at each Cairo
    frame's time the page is sought through mo2dViewer.seek(t), and at every pixel centre that
    mo2dViewer.jointPositions() reports, BOTH the page's screenshot and the Cairo PNG of that
    time must show a pin (a light disc inside a dark ring of the style's joint radius): a drawing
    off by more than a pixel or two puts the ring across the centre or leaves a side of it empty;
  - a contact's circle around its point (and a circle's or a hole's target) that is not drawn
    where mo2dViewer.contactPositions() says, in its colour, on both the page and the Cairo frame;
  - the same pin check after zooming the page 2x about its centre (ring radius doubled);
  - playback that does not advance, a click panel (select) without the joint's values (the
    first body's name without joints).
Exits 77 (ctest SKIP_RETURN_CODE) with a message when chromium is not installed.
"""
import base64
import fcntl
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time
import zlib

SKIP = 77


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


# ---- PNG decoding (8-bit RGB / RGBA, not interlaced: what Chromium and mo2d write) -------------
# Rows are unfiltered when first read (the Sub filter of mo2d's encoder needs no other row; Up,
# Average and Paeth need the row above): a pin check reads a few rows of a Cairo frame only.
def read_png(data, origin=(0, 0)):
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        fail("not a PNG")
    pos, idat = 8, b""
    while pos < len(data):
        n = int.from_bytes(data[pos:pos + 4], "big")
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + n]
        pos += 12 + n
        if kind == b"IHDR":
            width, height = int.from_bytes(body[0:4], "big"), int.from_bytes(body[4:8], "big")
            depth, ctype, interlace = body[8], body[9], body[12]
            if depth != 8 or ctype not in (2, 6) or interlace:
                fail("PNG of depth %d colour type %d interlace %d not read" % (depth, ctype, interlace))
        elif kind == b"IDAT":
            idat += body
    return {"w": width, "h": height, "bpp": 3 if ctype == 2 else 4, "raw": zlib.decompress(idat),
            "rows": {}, "ox": origin[0], "oy": origin[1]}


def png_row(img, y):
    rows = img["rows"]
    if y in rows:
        return rows[y]
    bpp, raw = img["bpp"], img["raw"]
    stride = img["w"] * bpp
    f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
    prev = png_row(img, y - 1) if f in (2, 3, 4) and y > 0 else bytes(stride)
    for i in range(stride):
        a = line[i - bpp] if i >= bpp else 0
        b, c = prev[i], prev[i - bpp] if i >= bpp else 0
        if f == 1:
            line[i] = (line[i] + a) & 255
        elif f == 2:
            line[i] = (line[i] + b) & 255
        elif f == 3:
            line[i] = (line[i] + (a + b) // 2) & 255
        elif f == 4:
            p = a + b - c
            pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
            line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
    rows[y] = bytes(line)
    return rows[y]


def luma(img, x, y):
    x, y = math.floor(x) - img["ox"], math.floor(y) - img["oy"]  # pixel i covers [i, i + 1)
    if not (0 <= x < img["w"] and 0 <= y < img["h"]):
        return 255
    r, i = png_row(img, y), x * img["bpp"]
    return 0.299 * r[i] + 0.587 * r[i + 1] + 0.114 * r[i + 2]


def pin_at(img, cx, cy, radius):
    """A pin centred at (cx, cy): light inside (r < radius / 3), and a dark ring at the radius
    (pixel centres within 1.2 px of it) in each of 16 sectors. Returns (ok, why)."""
    for dx, dy in ((0, 0), (1, 0), (-1, 0), (0, 1), (0, -1)):
        if luma(img, cx + dx * 0.3 * radius, cy + dy * 0.3 * radius) < 170:
            return False, "centre is dark (luma %.0f)" % luma(img, cx, cy)
    darkest = [255.0] * 16
    reach = int(radius + 3)
    for j in range(math.floor(cy) - reach, math.floor(cy) + reach + 1):
        for i in range(math.floor(cx) - reach, math.floor(cx) + reach + 1):
            dx, dy = i + 0.5 - cx, j + 0.5 - cy
            if abs(math.hypot(dx, dy) - radius) <= 1.2:
                k = int(((math.atan2(dy, dx) + math.pi / 16) % (2 * math.pi)) / (math.pi / 8)) % 16
                darkest[k] = min(darkest[k], luma(img, i, j))
    for k, d in enumerate(darkest):
        if d > 120:
            return False, "no ring at %g degrees (darkest luma %.0f)" % (22.5 * k, d)
    return True, ""


def pixel(img, x, y):
    x, y = math.floor(x) - img["ox"], math.floor(y) - img["oy"]
    if not (0 <= x < img["w"] and 0 <= y < img["h"]):
        return (255, 255, 255)
    r, i = png_row(img, y), x * img["bpp"]
    return (r[i], r[i + 1], r[i + 2])


def ring_at(img, cx, cy, radius, ink):
    """A circle of `radius` around (cx, cy) stroked in `ink` (RGB 0-255): in at least 12 of 16
    sectors a pixel centre within 1.2 px of the radius within 60 of the ink (other shapes drawn
    later may cover a few sectors). Returns (ok, why)."""
    found = [False] * 16
    reach = int(radius + 3)
    for j in range(math.floor(cy) - reach, math.floor(cy) + reach + 1):
        for i in range(math.floor(cx) - reach, math.floor(cx) + reach + 1):
            dx, dy = i + 0.5 - cx, j + 0.5 - cy
            if abs(math.hypot(dx, dy) - radius) <= 1.2:
                k = int(((math.atan2(dy, dx) + math.pi / 16) % (2 * math.pi)) / (math.pi / 8)) % 16
                c = pixel(img, i, j)
                if max(abs(c[n] - ink[n]) for n in range(3)) <= 60:
                    found[k] = True
    if sum(found) < 12:
        return False, "the ink %s in %d of 16 sectors" % (ink, sum(found))
    return True, ""


def best_offset(img, cx, cy, radius):
    """Where, within 6 px, a pin is found nearest to (cx, cy) (for the failure message)."""
    found = [(math.hypot(dx, dy), dx, dy) for dx in range(-6, 7) for dy in range(-6, 7)
             if pin_at(img, cx + dx, cy + dy, radius)[0]]
    return min(found)[1:] if found else None


# ---- Chromium over the DevTools protocol (a pipe: fd 3 to the browser, fd 4 from it) -----------
class Browser:
    def __init__(self, chromium, profile):
        to_r, self.to_w = os.pipe()
        self.from_r, from_w = os.pipe()

        def child_fds():  # fd 3 and 4 in the browser (above 9 first: to_r or from_w may be 3 or 4)
            r, w = fcntl.fcntl(to_r, fcntl.F_DUPFD, 10), fcntl.fcntl(from_w, fcntl.F_DUPFD, 10)
            os.dup2(r, 3)
            os.dup2(w, 4)

        args = [chromium, "--headless", "--remote-debugging-pipe", "--no-sandbox", "--disable-gpu",
                "--no-first-run", "--no-default-browser-check", "--disable-extensions",
                "--hide-scrollbars", "--mute-audio", "--user-data-dir=" + profile,
                "--window-size=1400,1200", "about:blank"]
        self.proc = subprocess.Popen(args, pass_fds=(3, 4), preexec_fn=child_fds,
                                     stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.close(to_r)
        os.close(from_w)
        self.buf, self.next_id, self.events = b"", 0, []

    def _read_message(self, deadline):
        while b"\0" not in self.buf:
            if time.monotonic() > deadline:
                fail("the browser did not answer in time")
            chunk = os.read(self.from_r, 1 << 20)
            if not chunk:
                fail("the browser closed the pipe (exit status %s)" % self.proc.poll())
            self.buf += chunk
        msg, self.buf = self.buf.split(b"\0", 1)
        return json.loads(msg)

    def call(self, method, params=None, session=None, timeout=10):
        self.next_id += 1
        msg = {"id": self.next_id, "method": method, "params": params or {}}
        if session:
            msg["sessionId"] = session
        os.write(self.to_w, json.dumps(msg).encode() + b"\0")
        deadline = time.monotonic() + timeout
        while True:
            m = self._read_message(deadline)
            if m.get("id") == self.next_id:
                if "error" in m:
                    fail("%s: %s" % (method, m["error"]))
                return m["result"]
            self.events.append(m)

    def wait_event(self, method, timeout=10):
        deadline = time.monotonic() + timeout
        for i, m in enumerate(self.events):
            if m.get("method") == method:
                return self.events.pop(i)
        while True:
            m = self._read_message(deadline)
            if m.get("method") == method:
                return m
            self.events.append(m)

    def close(self):
        try:
            self.call("Browser.close", timeout=5)
        except SystemExit:
            pass
        try:
            self.proc.wait(timeout=5)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()


def run(cmd):
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        fail("%s: exit %d\n%s%s" % (" ".join(cmd), p.returncode, p.stdout, p.stderr))
    return p.stdout


def main():
    argv, run_settings = sys.argv[1:], []
    if "--" in argv:
        argv, run_settings = argv[:argv.index("--")], argv[argv.index("--") + 1:]
    every, max_frames = 50, 400
    if "--every" in argv:
        i = argv.index("--every")
        every = int(argv[i + 1])
        del argv[i:i + 2]
    if "--max-frames" in argv:
        i = argv.index("--max-frames")
        max_frames = int(argv[i + 1])
        del argv[i:i + 2]
    mo2d, scene, out = argv
    chromium = os.environ.get("MO2D_CHROMIUM") or shutil.which("chromium") or \
        shutil.which("chromium-browser")
    if not chromium:
        print("SKIP: chromium is not installed (Debian package chromium; scripts/install-deps.sh)")
        return SKIP
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    page = os.path.join(out, "page.html")
    said = run([mo2d, "view", scene, "-o", page, "--max-frames", str(max_frames)] + run_settings)
    run([mo2d, "render", scene, "--frames", "--every", str(every), "--out",
         os.path.join(out, "cairo")] + run_settings)
    frames = sorted(f for f in os.listdir(os.path.join(out, "cairo")) if f[-9:-4].lstrip("_").isdigit())
    print(said.strip())
    print("%d Cairo frames every %d samples" % (len(frames), every))

    profile = tempfile.mkdtemp(prefix="mo2d-chromium-")
    b = Browser(chromium, profile)
    try:
        target = b.call("Target.createTarget", {"url": "about:blank"})["targetId"]
        s = b.call("Target.attachToTarget", {"targetId": target, "flatten": True})["sessionId"]
        for domain in ("Runtime", "Log", "Page", "Network"):
            b.call(domain + ".enable", session=s)
        b.call("Emulation.setDeviceMetricsOverride",
               {"width": 1400, "height": 1200, "deviceScaleFactor": 1, "mobile": False}, session=s)
        b.call("Page.navigate", {"url": "file://" + os.path.abspath(page)}, session=s)
        b.wait_event("Page.loadEventFired")

        def js(expr):
            r = b.call("Runtime.evaluate", {"expression": expr, "returnByValue": True}, session=s)
            if "exceptionDetails" in r:
                fail("%s: %s" % (expr, json.dumps(r["exceptionDetails"])[:600]))
            return r["result"].get("value")

        shots = []

        def screenshot_around(rect, x, y, reach):
            """A screenshot of the square of `reach` pixels around canvas pixel (x, y), kept
            beside the Cairo frames (to look at after a failure)."""
            x0, y0 = math.floor(x) - reach, math.floor(y) - reach
            clip = {"x": rect["x"] + x0, "y": rect["y"] + y0, "width": 2 * reach + 1,
                    "height": 2 * reach + 1, "scale": 1}
            shot = b.call("Page.captureScreenshot",
                          {"format": "png", "clip": clip, "fromSurface": True}, session=s)
            data = base64.b64decode(shot["data"])
            shots.append(data)
            with open(os.path.join(out, "page_%03d.png" % len(shots)), "wb") as f:
                f.write(data)
            return read_png(data, (x0, y0))

        if not js("!!(window.mo2dViewer && window.mo2dViewer.ready)"):
            fail("the page has no ready window.mo2dViewer")
        first = js("mo2dViewer.firstFrameMs")
        print("first frame %.0f ms after navigation" % first)
        if first > 2000:
            fail("first frame %.0f ms after navigation" % first)
        rect = js("mo2dViewer.canvasRect()")
        radius = js("MO2D.style.joint_r")
        times = js("mo2dViewer.times")
        stride = js("MO2D.stride")
        checked = 0
        for n, name in enumerate(frames):
            sample = n * every
            if sample % stride:
                fail("sample %d of Cairo frame %s is not in the page (stride %d)" % (sample, name, stride))
            t = times[min(sample // stride, len(times) - 1)]
            got = js("mo2dViewer.seek(%r)" % t)
            if abs(got - t) > 1e-12:
                fail("seek(%r) went to %r" % (t, got))
            joints = js("mo2dViewer.jointPositions()")
            with open(os.path.join(out, "cairo", name), "rb") as f:
                cairo = read_png(f.read())
            for j in joints:
                if j["kind"] == "prismatic":
                    continue
                shot = screenshot_around(rect, j["x"], j["y"], int(radius + 9))
                for what, img in (("page", shot), ("Cairo frame", cairo)):
                    ok, why = pin_at(img, j["x"], j["y"], radius)
                    if not ok:
                        fail("t = %g s, joint '%s' at page pixel (%.2f, %.2f): the %s has no pin "
                             "there: %s; nearest pin offset %s" %
                             (t, j["name"], j["x"], j["y"], what, why,
                              best_offset(img, j["x"], j["y"], radius)))
                checked += 1
            for c in js("mo2dViewer.contactPositions()"):
                rings = [("circle around '%s'" % c["name"], c["x"], c["y"], c["r"], c["ink"])]
                if c["target"] in ("circle", "hole"):
                    rings.append(("target of '%s'" % c["name"], c["ax"], c["ay"], c["R"],
                                  c["target_ink"]))
                for what_ring, x, y, r, ink in rings:
                    if r > 150:
                        continue
                    shot = screenshot_around(rect, x, y, int(r + 5))
                    for what, img in (("page", shot), ("Cairo frame", cairo)):
                        ok, why = ring_at(img, x, y, r, ink)
                        if not ok:
                            fail("t = %g s, the %s at page pixel (%.2f, %.2f), radius %.2f: the "
                                 "%s has no such ring: %s" % (t, what_ring, x, y, r, what, why))
                    checked += 1
        # zoomed 2x about the centre: the pins move and grow with the zoom
        js("mo2dViewer.setZoom(2)")
        for j in js("mo2dViewer.jointPositions()"):
            inside = 20 < j["x"] < rect["width"] - 20 and 20 < j["y"] < rect["height"] - 20
            if j["kind"] != "prismatic" and inside:
                shot = screenshot_around(rect, j["x"], j["y"], int(2 * radius + 9))
                ok, why = pin_at(shot, j["x"], j["y"], 2 * radius)
                if not ok:
                    fail("zoom 2: joint '%s' at (%.2f, %.2f): %s" % (j["name"], j["x"], j["y"], why))
                checked += 1
        js("mo2dViewer.resetView()")
        # the click panel and playback
        joints = js("mo2dViewer.jointPositions()")
        if joints:
            joint = joints[0]["name"]
            info = js("mo2dViewer.select(%s)" % json.dumps(joint))
            if joint not in info or "position" not in info:
                fail("select(%r) shows %r" % (joint, info))
        else:  # a mechanism without joints (a bouncing ball): its first body
            body = js("MO2D.bodies[0].name")
            info = js("mo2dViewer.select(%s)" % json.dumps(body))
            if body not in info:
                fail("select(%r) shows %r" % (body, info))
        js("mo2dViewer.seekFrame(0); mo2dViewer.play()")
        time.sleep(0.3)
        t_played = js("mo2dViewer.pause(), mo2dViewer.time()")
        if not t_played > times[0]:
            fail("playing 0.3 s left the page at t = %r" % t_played)

        errors = js("mo2dViewer.errors")
        for m in b.events:
            method, p = m.get("method"), m.get("params", {})
            if method == "Runtime.consoleAPICalled" and p.get("type") in ("error", "assert"):
                errors.append("console.%s: %s" % (p["type"], [a.get("value") for a in p["args"]]))
            elif method == "Runtime.exceptionThrown":
                errors.append("exception: %s" % json.dumps(p["exceptionDetails"])[:400])
            elif method == "Log.entryAdded" and p["entry"]["level"] == "error":
                errors.append("log: %s" % p["entry"]["text"])
            elif method == "Network.requestWillBeSent":
                url = p["request"]["url"]
                if not url.startswith(("file:", "data:", "about:")):
                    errors.append("the page fetched %s" % url)
        if errors:
            fail("errors on the page:\n  " + "\n  ".join(errors))
        print("OK: %d pins at %d times agree with the Cairo frames (and at zoom 2); played to t = %g s"
              % (checked, len(frames), t_played))
    finally:
        b.close()
        shutil.rmtree(profile, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
