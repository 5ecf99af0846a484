#!/usr/bin/env python3
"""ahhs-capture: ahhs-view's page in headless Chromium (docs/viewer.md).

Chromium (Debian's `chromium`) is driven over the DevTools protocol on a pipe
(--remote-debugging-pipe: no debugging port is opened), renders with SwiftShader (no GPU,
no display), and the page's own API (window.ahhs) positions each frame.

  ahhs-capture probe URL [--wait EXPR] [--eval EXPR] [--screenshot PNG] [--hold S]
      load the page, wait until EXPR is true (default: the page shows a frame), print the
      JSON value of EXPR (default: ahhs.stats()), optionally save a screenshot
  ahhs-capture video URL OUT.mp4 [--fps 25] [--from S] [--to S] [--size 1280x720]
      one frame per 1/fps of simulated time, piped to ffmpeg: H.264, yuv420p
  ahhs-capture filmstrip URL OUT.png [--frames 8] [--size 1280x720]
      frames spread evenly over the episode, in a grid of 4 columns

Exit codes: 0 done, 1 failed (Chromium, the page or ffmpeg; one line on stderr), 2 usage,
130 interrupted (SIGINT), 143 terminated (SIGTERM); on every exit Chromium is closed and its
temporary profile removed, and no partial output is left.
Output files are written under a temporary name and renamed when complete.
"""

import argparse
import base64
import io
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time

PROG = "ahhs-capture"


class CaptureError(Exception):
    pass


class Chromium:
    """A headless Chromium and one page, over the DevTools pipe (fd 3 in, fd 4 out)."""

    def __init__(self, width, height, timeout=60.0):
        self.timeout = timeout
        exe = shutil.which("chromium") or shutil.which("chromium-browser")
        if not exe:
            raise CaptureError("chromium not found (tools/install-deps installs Debian's chromium)")
        self.proc = None
        self.profile = tempfile.mkdtemp(prefix="ahhs-capture-")
        try:
            self._start(exe, width, height)
        except BaseException:
            self.close()  # a Chromium that did not come up leaves no process and no profile
            raise

    def _start(self, exe, width, height):
        to_chrome_r, self.to_chrome = os.pipe()
        self.from_chrome, from_chrome_w = os.pipe()

        def fds():
            # Chromium reads fd 3 and writes fd 4. The pipe's own fds may be 3 or 4 already:
            # move both out of the way first, and make the results inheritable.
            a, b = os.dup(to_chrome_r), os.dup(from_chrome_w)
            os.dup2(a, 3, inheritable=True)
            os.dup2(b, 4, inheritable=True)

        args = [exe, "--headless=new", "--remote-debugging-pipe", "--user-data-dir=" + self.profile,
                "--no-first-run", "--no-default-browser-check", "--disable-extensions",
                "--mute-audio", "--hide-scrollbars", "--use-angle=swiftshader",
                "--enable-unsafe-swiftshader", "--disable-background-timer-throttling",
                "--disable-renderer-backgrounding", "--force-device-scale-factor=1",
                f"--window-size={width},{height}", "about:blank"]
        if os.geteuid() == 0:
            args.insert(1, "--no-sandbox")  # Chromium's sandbox refuses to run as root
        self.proc = subprocess.Popen(args, preexec_fn=fds, close_fds=False,
                                     stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                     stderr=subprocess.PIPE)
        os.close(to_chrome_r)
        os.close(from_chrome_w)
        self.buffer = b""
        self.next_id = 0
        self.errors = []
        self.session = None
        target = self.call("Target.createTarget", {"url": "about:blank"})["targetId"]
        self.session = self.call("Target.attachToTarget",
                                 {"targetId": target, "flatten": True})["sessionId"]
        self.call("Runtime.enable")
        self.call("Page.enable")
        self.call("Emulation.setDeviceMetricsOverride",
                  {"width": width, "height": height, "deviceScaleFactor": 1, "mobile": False})

    def _read_message(self, deadline):
        while b"\0" not in self.buffer:
            if time.monotonic() > deadline:
                raise CaptureError("chromium did not answer within %.0f s" % self.timeout)
            import select
            ready, _, _ = select.select([self.from_chrome], [], [], 0.5)
            if not ready:
                if self.proc.poll() is not None:
                    raise CaptureError("chromium exited (%s): %s" % (
                        self.proc.returncode, self._stderr_tail()))
                continue
            chunk = os.read(self.from_chrome, 1 << 20)
            if not chunk:
                raise CaptureError("chromium closed its DevTools pipe: " + self._stderr_tail())
            self.buffer += chunk
        raw, self.buffer = self.buffer.split(b"\0", 1)
        return json.loads(raw)

    def _stderr_tail(self):
        try:
            self.proc.kill()
            err = self.proc.stderr.read().decode(errors="replace").strip().splitlines()
            useful = [l for l in err if "dbus" not in l.lower()]
            return useful[-1] if useful else "no message"
        except Exception:  # noqa: BLE001 - best effort for an error message
            return "no message"

    def call(self, method, params=None):
        self.next_id += 1
        msg = {"id": self.next_id, "method": method, "params": params or {}}
        if self.session:
            msg["sessionId"] = self.session
        os.write(self.to_chrome, json.dumps(msg).encode() + b"\0")
        deadline = time.monotonic() + self.timeout
        while True:
            m = self._read_message(deadline)
            if m.get("id") == self.next_id:
                if "error" in m:
                    raise CaptureError("%s: %s" % (method, m["error"].get("message")))
                return m.get("result", {})
            if m.get("method") == "Runtime.exceptionThrown":
                d = m["params"]["exceptionDetails"]
                self.errors.append(d.get("exception", {}).get("description") or d.get("text"))

    def evaluate(self, expression, await_promise=False):
        r = self.call("Runtime.evaluate", {"expression": expression, "returnByValue": True,
                                           "awaitPromise": await_promise})
        if "exceptionDetails" in r:
            d = r["exceptionDetails"]
            raise CaptureError("the page: " + (d.get("exception", {}).get("description") or
                                               d.get("text", "")).splitlines()[0])
        return r["result"].get("value")

    def open(self, url, wait="window.ahhs && ahhs.isReady()"):
        nav = self.call("Page.navigate", {"url": url})
        if nav.get("errorText"):
            raise CaptureError("cannot load %s: %s" % (url, nav["errorText"]))
        deadline = time.monotonic() + self.timeout
        while True:
            try:
                if self.evaluate(wait):
                    break
            except CaptureError:
                pass  # the page is still loading
            if self.errors:
                raise CaptureError("the page threw: " + self.errors[0].splitlines()[0])
            if time.monotonic() > deadline:
                raise CaptureError("the page at %s was not ready within %.0f s (%s)"
                                   % (url, self.timeout, wait))
            time.sleep(0.1)

    def screenshot(self, fmt="png", quality=None):
        params = {"format": fmt, "optimizeForSpeed": True}
        if quality:
            params["quality"] = quality
        return base64.b64decode(self.call("Page.captureScreenshot", params)["data"])

    def close(self):
        if self.proc is None:  # Chromium never started: only the pipes and the profile
            for fd in (getattr(self, "to_chrome", None), getattr(self, "from_chrome", None)):
                if fd is not None:
                    os.close(fd)
            shutil.rmtree(self.profile, ignore_errors=True)
            return
        if self.proc.poll() is None:
            try:
                self.call("Browser.close")
            except CaptureError:
                pass
        try:
            self.proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()
        for fd in (self.to_chrome, self.from_chrome):
            try:
                os.close(fd)
            except OSError:
                pass
        shutil.rmtree(self.profile, ignore_errors=True)


def parse_size(text):
    try:
        w, h = (int(v) for v in text.split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError("must be WIDTHxHEIGHT") from None
    return w, h


def probe(args):
    chrome = Chromium(*args.size, timeout=args.timeout)
    try:
        chrome.open(args.url, args.wait)
        if args.hold:
            time.sleep(args.hold)
        value = chrome.evaluate(args.eval, await_promise=True)
        if args.screenshot:
            with open(args.screenshot, "wb") as f:
                f.write(chrome.screenshot())
        if chrome.errors:
            raise CaptureError("the page threw: " + chrome.errors[0].splitlines()[0])
        print(json.dumps(value))
    finally:
        chrome.close()


def new_temp_beside(path, suffix):
    """A new file beside `path` for writing under a temporary name (O_EXCL: never an existing
    file or a planted symlink), with the permissions any new file of this process gets."""
    folder, name = os.path.split(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(prefix=name + ".tmp-", suffix=suffix, dir=folder)
    os.close(fd)
    mask = os.umask(0)
    os.umask(mask)
    os.chmod(tmp, 0o666 & ~mask)
    return tmp


def video(args):
    """Frames are rendered by --jobs Chromiums at once (frame i by Chromium i % jobs) and piped
    to ffmpeg in order through small queues, so memory stays bounded for any length."""
    import queue
    import threading
    ffmpeg = shutil.which("ffmpeg")
    if not ffmpeg:
        raise CaptureError("ffmpeg not found (tools/install-deps installs it)")
    tmp = new_temp_beside(args.out, ".mp4")
    chromes, enc = [], None
    try:
        for _ in range(args.jobs):
            chromes.append(Chromium(*args.size, timeout=args.timeout))
        for chrome in chromes:
            chrome.open(args.url + "?capture=1")
        end = chromes[0].evaluate("ahhs.duration()")
        start = args.start
        if args.to is not None:
            end = min(end, args.to)
        if end <= start:
            raise CaptureError("nothing to film: the episode ends at %.2f s, --from is %.2f s"
                               % (end, start))
        frames = int(round((end - start) * args.fps))
        enc = subprocess.Popen([ffmpeg, "-y", "-loglevel", "error", "-f", "image2pipe",
                                "-framerate", str(args.fps), "-c:v", "mjpeg", "-i", "-",
                                "-c:v", "libx264", "-preset", "veryfast", "-crf", "22",
                                "-pix_fmt", "yuv420p", "-movflags", "+faststart", "-f", "mp4",
                                tmp], stdin=subprocess.PIPE, stderr=subprocess.PIPE)
        queues = [queue.Queue(maxsize=8) for _ in chromes]
        stop = threading.Event()

        def render(j):
            try:
                for i in range(j, frames, len(chromes)):
                    if stop.is_set():
                        return
                    chromes[j].evaluate("ahhs.renderAt(%r)" % (start + i / args.fps))
                    queues[j].put(chromes[j].screenshot("jpeg", 92))
            except Exception as e:  # noqa: BLE001 - handed to the main thread
                queues[j].put(e)

        began = time.monotonic()
        threads = [threading.Thread(target=render, args=(j,), daemon=True)
                   for j in range(len(chromes))]
        for t in threads:
            t.start()
        try:
            for i in range(frames):
                jpeg = queues[i % len(chromes)].get()
                if isinstance(jpeg, Exception):
                    raise jpeg
                enc.stdin.write(jpeg)
        finally:
            stop.set()
            for q in queues:  # unblock a renderer waiting on a full queue
                while not q.empty():
                    q.get_nowait()
            for t in threads:
                t.join()
        enc.stdin.close()
        if enc.wait() != 0:
            raise CaptureError("ffmpeg failed: " + enc.stderr.read().decode(errors="replace")
                               .strip().splitlines()[-1])
        for chrome in chromes:
            if chrome.errors:
                raise CaptureError("the page threw: " + chrome.errors[0].splitlines()[0])
        os.replace(tmp, args.out)
        took = time.monotonic() - began
        print("%s: %d frames, %.1f s of video in %.1f s (%.2f s of video per second)"
              % (args.out, frames, frames / args.fps, took, frames / args.fps / took))
    finally:
        if enc and enc.poll() is None:
            enc.kill()
            enc.wait()
        if os.path.exists(tmp):
            os.remove(tmp)
        for chrome in chromes:
            chrome.close()


def filmstrip(args):
    from PIL import Image  # python3-pil
    chrome = Chromium(*args.size, timeout=args.timeout)
    tmp = new_temp_beside(args.out, ".png")
    try:
        chrome.open(args.url + "?capture=1")
        end = chrome.evaluate("ahhs.duration()")
        shots = []
        for k in range(args.frames):
            t = end * (k + 0.5) / args.frames
            chrome.evaluate("ahhs.renderAt(%r)" % t)
            shots.append(Image.open(io.BytesIO(chrome.screenshot())).convert("RGB"))
        cols = min(4, args.frames)
        rows = (args.frames + cols - 1) // cols
        w, h = args.size[0] // 2, args.size[1] // 2
        sheet = Image.new("RGB", (cols * w, rows * h), "white")
        for k, shot in enumerate(shots):
            sheet.paste(shot.resize((w, h), Image.LANCZOS), ((k % cols) * w, (k // cols) * h))
        sheet.save(tmp, "PNG")
        os.replace(tmp, args.out)
        print("%s: %d frames of %.1f s" % (args.out, args.frames, end))
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)
        chrome.close()


def main():
    ap = argparse.ArgumentParser(prog=PROG, description=__doc__.split("\n")[0])
    ap.add_argument("--version", action="version",  # the wrapper passes the build's version
                    version=f"{PROG} {os.environ.get('AHHS_VERSION', 'unknown')}")
    sub = ap.add_subparsers(dest="cmd", required=True)
    common = argparse.ArgumentParser(add_help=False)
    common.add_argument("--size", type=parse_size, default=(1280, 720))
    common.add_argument("--timeout", type=float, default=60.0,
                        help="seconds to wait for Chromium or the page")
    p = sub.add_parser("probe", parents=[common])
    p.add_argument("url")
    p.add_argument("--wait", default="window.ahhs && ahhs.isReady()")
    p.add_argument("--eval", default="ahhs.stats()")
    p.add_argument("--screenshot")
    p.add_argument("--hold", type=float, default=0)
    v = sub.add_parser("video", parents=[common])
    v.add_argument("url")
    v.add_argument("out")
    v.add_argument("--fps", type=int, default=25)
    v.add_argument("--from", dest="start", type=float, default=0.0)
    v.add_argument("--to", type=float)
    v.add_argument("--jobs", type=int, default=min(2, os.cpu_count() or 1),
                   help="Chromiums rendering at once (default: up to 2)")
    f = sub.add_parser("filmstrip", parents=[common])
    f.add_argument("url")
    f.add_argument("out")
    f.add_argument("--frames", type=int, default=8)
    args = ap.parse_args()
    # SIGTERM (a test's `kill`, a job scheduler) unwinds like SIGINT, so the `finally` blocks
    # close Chromium and remove its profile instead of leaving both behind.
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(143))
    try:
        {"probe": probe, "video": video, "filmstrip": filmstrip}[args.cmd](args)
    except CaptureError as e:
        print("%s: %s" % (PROG, e), file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        return 130
    return 0


if __name__ == "__main__":
    sys.exit(main())
