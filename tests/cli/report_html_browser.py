#!/usr/bin/python3
"""Opens HTML reports in headless Chromium and checks what a reader's browser does with them (issue 29).

ONE Chromium runs for all the reports (a start costs seconds of CPU): it is driven over the DevTools protocol on a
pipe (--remote-debugging-pipe: JSON messages on file descriptors 3 and 4, no port, no websocket library). For each
REPORT.html a copy is made with the Content-Security-Policy removed (so that a load the page attempted would really
be asked for and seen) and opened in a fresh tab of 1280 x 800 px:
  console       every console message, exception and browser log entry of the page (Runtime, Log): there must be
                none;
  requests      every request the page makes (Network.requestWillBeSent, and the Fetch domain, which records and
                fails at once every http(s)/ws(s) request so that none waits on the network): none may leave the
                file (file: and data: only);
  measurements  a script evaluated after the load event: each <figure>'s <svg> bounding box (not empty), the answer
                block (class "answer") within the first screen;
  outputs       the first screen (Page.captureScreenshot, PNG) and the print (Page.printToPDF with the print
                stylesheet's paper) written to OUTDIR as NAME-first-screen.png and NAME.pdf.
Usage: report_html_browser.py CHROMIUM OUTDIR REPORT.html... ; exit 1 listing every failure, 77 when Chromium
cannot start here (the reason printed)."""
import base64
import json
import os
import re
import select
import shutil
import subprocess
import sys
import tempfile
import time

WIDTH, HEIGHT = 1280, 800  # the first screen: a laptop's browser window

MEASURE = """(function () {
  var r = {viewport: [window.innerWidth, window.innerHeight], figures: [], answers: []};
  document.querySelectorAll('.answer').forEach(function (a) { r.answers.push(a.getBoundingClientRect().toJSON()); });
  document.querySelectorAll('figure').forEach(function (f) {
    var s = f.querySelector('svg'), b = (s || f).getBoundingClientRect();
    r.figures.push({id: f.id, svg: !!s, w: b.width, h: b.height});
  });
  r.resources = performance.getEntriesByType('resource').map(function (e) { return e.name; });
  return JSON.stringify(r);
})()"""

FLAGS = ["--headless", "--disable-gpu", "--no-sandbox", "--disable-dev-shm-usage", "--hide-scrollbars",
         "--disable-background-networking", "--disable-component-update", "--disable-sync", "--no-first-run",
         "--disable-default-apps", "--disable-extensions", "--mute-audio", "--remote-debugging-pipe",
         f"--window-size={WIDTH},{HEIGHT}"]


class Browser:
    """Chromium over --remote-debugging-pipe: send() a command, wait for its answer; events are queued."""

    def __init__(self, chromium, profile):
        to_chrome_r, self.to_chrome = os.pipe()
        self.from_chrome, from_chrome_w = os.pipe()

        def fds():  # the child reads commands on fd 3 and writes answers and events on fd 4 (close_fds=False: closing
            # would take 3 and 4 too; the pipes' own fds are CLOEXEC, so nothing else leaks)
            r, w = os.dup(to_chrome_r), os.dup(from_chrome_w)  # the pipes may already sit on 3 or 4
            os.dup2(r, 3)
            os.dup2(w, 4)
            os.set_inheritable(3, True)
            os.set_inheritable(4, True)

        env = dict(os.environ, DBUS_SESSION_BUS_ADDRESS="disabled:")
        self.log = open(os.path.join(profile, "chromium.log"), "w+")
        self.proc = subprocess.Popen([chromium] + FLAGS + [f"--user-data-dir={profile}", "about:blank"],
                                     preexec_fn=fds, close_fds=False, stdout=self.log, stderr=self.log, env=env)
        os.close(to_chrome_r)
        os.close(from_chrome_w)
        self.buf, self.next_id, self.events = b"", 0, []

    def _read(self, deadline):
        while b"\0" not in self.buf:
            left = deadline - time.monotonic()
            if left <= 0:
                raise TimeoutError("no answer from Chromium")
            ready, _, _ = select.select([self.from_chrome], [], [], left)
            if ready:
                chunk = os.read(self.from_chrome, 1 << 20)
                if not chunk:
                    raise EOFError("Chromium closed its pipe")
                self.buf += chunk
        msg, self.buf = self.buf.split(b"\0", 1)
        m = json.loads(msg)
        if m.get("method") == "Fetch.requestPaused":  # recorded (the event stays queued) and failed at once
            self.post("Fetch.failRequest", {"requestId": m["params"]["requestId"], "errorReason": "BlockedByClient"},
                      m.get("sessionId"))
        return m

    def post(self, method, params, session=None):
        """Sends without waiting (the answer is queued with the events and ignored)."""
        self.next_id += 1
        msg = {"id": self.next_id, "method": method, "params": params}
        if session:
            msg["sessionId"] = session
        os.write(self.to_chrome, json.dumps(msg).encode() + b"\0")

    def send(self, method, params=None, session=None, timeout=60):
        self.post(method, params or {}, session)
        want = self.next_id
        deadline = time.monotonic() + timeout
        while True:
            m = self._read(deadline)
            if m.get("id") == want:
                if "error" in m:
                    raise RuntimeError(f"{method}: {m['error'].get('message')}")
                return m.get("result", {})
            self.events.append(m)

    def wait_event(self, method, session, timeout):
        """Waits for `method` in `session` (queued or new); False on timeout."""
        deadline = time.monotonic() + timeout
        while True:
            for e in self.events:
                if e.get("method") == method and e.get("sessionId") == session:
                    return True
            try:
                self.events.append(self._read(deadline))
            except TimeoutError:
                return False

    def close(self):
        try:
            self.send("Browser.close", timeout=10)
        except Exception:  # noqa: BLE001 -- it may be gone already
            pass
        try:
            self.proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()


def check_page(b, path, work, outdir):
    name = os.path.splitext(os.path.basename(path))[0]
    src = open(path, encoding="utf-8").read()
    copy = re.sub(r'<meta http-equiv="Content-Security-Policy"[^>]*>', "", src, count=1)
    page = os.path.join(work, name + ".html")
    open(page, "w", encoding="utf-8").write(copy)
    url = "file://" + os.path.abspath(page)
    png = os.path.join(outdir, name + "-first-screen.png")
    pdf = os.path.join(outdir, name + ".pdf")
    for stale in (png, pdf):
        if os.path.exists(stale):
            os.remove(stale)
    target = b.send("Target.createTarget", {"url": "about:blank"})["targetId"]
    s = b.send("Target.attachToTarget", {"targetId": target, "flatten": True})["sessionId"]
    for domain in ("Page", "Runtime", "Log", "Network"):
        b.send(domain + ".enable", session=s)
    b.send("Fetch.enable", {"patterns": [{"urlPattern": p} for p in ("http:*", "https:*", "ws:*", "wss:*")]},
           session=s)
    b.send("Emulation.setDeviceMetricsOverride", {"width": WIDTH, "height": HEIGHT, "deviceScaleFactor": 1,
                                                  "mobile": False}, session=s)
    b.send("Page.navigate", {"url": url}, session=s)
    bad = []
    if not b.wait_event("Page.loadEventFired", s, 60):
        bad.append("the page did not finish loading within 60 s")
    res = b.send("Runtime.evaluate", {"expression": MEASURE, "returnByValue": True}, session=s)
    try:
        meas = json.loads(res["result"]["value"])
    except (KeyError, TypeError, ValueError):
        bad.append(f"the measuring script failed: {str(res)[:200]}")
        meas = {"figures": [], "answers": [], "resources": [], "viewport": [WIDTH, HEIGHT]}
    shot = b.send("Page.captureScreenshot", {"format": "png"}, session=s)
    open(png, "wb").write(base64.b64decode(shot["data"]))
    printed = b.send("Page.printToPDF", {"preferCSSPageSize": True, "printBackground": True,
                                         "displayHeaderFooter": False}, session=s, timeout=120)
    open(pdf, "wb").write(base64.b64decode(printed["data"]))
    # what the page did: its events (a request Fetch paused is failed at once, so none waits on the network)
    requests = []
    for e in b.events:
        if e.get("sessionId") != s:
            continue
        m, p = e.get("method"), e.get("params", {})
        if m == "Runtime.consoleAPICalled":
            text = " ".join(str(a.get("value", a.get("description", ""))) for a in p.get("args", []))
            bad.append(f"console: CONSOLE {p.get('type')}: {text[:200]}")
        elif m == "Runtime.exceptionThrown":
            bad.append(f"console: CONSOLE exception: {p.get('exceptionDetails', {}).get('text', '')[:200]}")
        elif m == "Log.entryAdded":
            entry = p.get("entry", {})
            bad.append(f"console: CONSOLE {entry.get('level')}: {entry.get('text', '')[:200]} {entry.get('url', '')}")
        elif m == "Network.requestWillBeSent":
            requests.append(p.get("request", {}).get("url", ""))
        elif m == "Fetch.requestPaused":  # failed when it came (Browser._read)
            requests.append(p.get("request", {}).get("url", ""))
    b.events = [e for e in b.events if e.get("sessionId") != s]
    b.send("Target.closeTarget", {"targetId": target})
    bad += [f"a request left the file: {u}" for u in dict.fromkeys(requests) if not u.startswith(("file:", "data:"))]
    bad += [f"the page fetched {u}" for u in meas["resources"] if not u.startswith(("data:", url))]
    for fig in meas["figures"]:
        if not fig["svg"] or fig["w"] <= 0 or fig["h"] <= 0:
            bad.append(f"figure {fig['id']} has an empty bounding box ({fig['w']} x {fig['h']}, svg {fig['svg']})")
    vh = meas["viewport"][1]
    if not meas["answers"]:
        bad.append("no answer block")
    for a in meas["answers"]:
        if not (a["height"] > 0 and a["top"] >= 0 and a["bottom"] <= vh):
            bad.append(f"the answer block ({a['top']:.0f}-{a['bottom']:.0f} px) is not within the first screen ({vh} px)")
    for out, magic in ((png, b"\x89PNG"), (pdf, b"%PDF")):
        if not os.path.exists(out) or os.path.getsize(out) < 1000 or open(out, "rb").read(4) != magic:
            bad.append(f"no {os.path.basename(out)} written")
    if not bad:
        print(f"ok {name}: {len(meas['figures'])} figures drawn, answer at {meas['answers'][0]['top']:.0f}-"
              f"{meas['answers'][0]['bottom']:.0f} px of {vh}, no console message, no request beyond the file; "
              f"{os.path.basename(png)}, {os.path.basename(pdf)}")
    return [f"{path}: {x}" for x in bad]


def main():
    chromium, outdir, reports = sys.argv[1], sys.argv[2], sys.argv[3:]
    os.makedirs(outdir, exist_ok=True)
    work = tempfile.mkdtemp(prefix="pounding-browser-")
    failures = []
    b = None
    try:
        try:
            b = Browser(chromium, work)
            b.send("Browser.getVersion", timeout=60)
        except Exception as e:  # noqa: BLE001 -- any start failure is the reason for the skip
            b.log.seek(0) if b else None
            tail = " ".join((b.log.read() if b else "").strip().splitlines()[-2:])[:300]
            print(f"SKIPPED: {chromium} cannot run headless here ({e}: {tail})")
            sys.exit(77)
        for path in reports:
            try:
                failures += check_page(b, path, work, outdir)
            except (RuntimeError, TimeoutError, EOFError) as e:
                failures.append(f"{path}: Chromium: {e}")
                if isinstance(e, EOFError):
                    break
    finally:
        if b:
            b.close()
        shutil.rmtree(work, ignore_errors=True)
    for f in failures:
        print(f"FAIL: {f}")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
