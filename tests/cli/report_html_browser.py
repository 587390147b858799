#!/usr/bin/python3
"""Opens HTML reports in headless Chromium and checks what a reader's browser does with them (issue 29).

For each REPORT.html a copy is made with the Content-Security-Policy removed (so that a load the page attempted
would really be made and seen) and a measuring script appended; Chromium loads it once with
  --dump-dom            the DOM after load, where the script left its measurements (bounding boxes, the resources
                        the page fetched: performance.getEntriesByType('resource'));
  --enable-logging=stderr --v=0   every console message of the page (CONSOLE lines): there must be none;
  --log-net-log         Chromium's own record of every URL request: a request whose network isolation key is the
                        file:// page must be for a file: or data: URL (Chromium's background requests, e.g. to
                        update servers, have another key and are not the page's);
  --screenshot --print-to-pdf   the first screen (PNG, the window size) and the print (PDF, the paper of the
                        print stylesheet), both written to OUTDIR.
Checks: no console message, no request leaves the file, every <figure>'s <svg> has a non-empty bounding box,
the answer block (class "answer") lies within the first screen, the PNG and the PDF exist and are not empty.
Usage: report_html_browser.py CHROMIUM OUTDIR REPORT.html... ; exit 1 listing every failure, 77 when Chromium
cannot start here (the reason printed)."""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

WIDTH, HEIGHT = 1280, 800  # the first screen: a laptop's browser window

MEASURE = """<div id="pounding-measure" hidden></div><script>
(function () {
  var r = {viewport: [window.innerWidth, window.innerHeight], figures: [], answers: []};
  document.querySelectorAll('.answer').forEach(function (a) { r.answers.push(a.getBoundingClientRect().toJSON()); });
  document.querySelectorAll('figure').forEach(function (f) {
    var s = f.querySelector('svg'), b = (s || f).getBoundingClientRect();
    r.figures.push({id: f.id, svg: !!s, w: b.width, h: b.height});
  });
  r.resources = performance.getEntriesByType('resource').map(function (e) { return e.name; });
  document.getElementById('pounding-measure').textContent = JSON.stringify(r);
})();
</script>"""

FLAGS = ["--headless", "--disable-gpu", "--no-sandbox", "--disable-dev-shm-usage", "--hide-scrollbars",
         "--disable-background-networking", "--disable-component-update", "--disable-sync", "--no-first-run",
         "--disable-default-apps", "--disable-extensions", "--mute-audio", "--no-pdf-header-footer",
         f"--window-size={WIDTH},{HEIGHT}", "--enable-logging=stderr", "--v=0"]


def run(chromium, profile, extra, url, timeout=120):
    env = dict(os.environ, DBUS_SESSION_BUS_ADDRESS="disabled:")
    return subprocess.run([chromium] + FLAGS + [f"--user-data-dir={profile}"] + extra + [url], capture_output=True,
                          text=True, timeout=timeout, env=env)


def page_requests(netlog):
    """URLs Chromium requested on behalf of a file:// page (its network isolation key is file://)."""
    try:
        d = json.load(open(netlog))
    except ValueError:  # a log cut short (Chromium exits before closing the array): close it
        text = open(netlog).read().rstrip().rstrip(",")
        d = json.loads(text + ("]}" if not text.endswith("}") else ""))
    types = {v: k for k, v in d["constants"]["logEventTypes"].items()}
    out = []
    for e in d.get("events", []):
        p = e.get("params") or {}
        if types.get(e["type"]) == "URL_REQUEST_START_JOB" and "url" in p:
            if "file://" in str(p.get("network_isolation_key", "")) or "file://" in str(p.get("site_for_cookies", "")):
                out.append(p["url"])
    return out


def main():
    chromium, outdir, reports = sys.argv[1], sys.argv[2], sys.argv[3:]
    os.makedirs(outdir, exist_ok=True)
    work = tempfile.mkdtemp(prefix="pounding-browser-")
    failures = []
    try:
        probe = run(chromium, os.path.join(work, "probe"), ["--dump-dom"], "about:blank", timeout=60)
        if probe.returncode != 0 or "<html" not in probe.stdout:
            tail = " ".join(probe.stderr.strip().splitlines()[-2:])[:300]
            print(f"SKIPPED: {chromium} cannot run headless here (exit {probe.returncode}: {tail})")
            sys.exit(77)
        for path in reports:
            name = os.path.splitext(os.path.basename(path))[0]
            src = open(path, encoding="utf-8").read()
            copy = re.sub(r'<meta http-equiv="Content-Security-Policy"[^>]*>', "", src, count=1)
            copy = copy.replace("</body>", MEASURE + "\n</body>", 1)
            page = os.path.join(work, name + ".html")
            open(page, "w", encoding="utf-8").write(copy)
            netlog = os.path.join(work, name + ".netlog.json")
            png = os.path.join(outdir, name + "-first-screen.png")
            pdf = os.path.join(outdir, name + ".pdf")
            for stale in (png, pdf):
                if os.path.exists(stale):
                    os.remove(stale)
            r = run(chromium, os.path.join(work, "profile-" + name),
                    ["--dump-dom", f"--screenshot={png}", f"--print-to-pdf={pdf}", f"--log-net-log={netlog}"],
                    "file://" + os.path.abspath(page))
            bad = []
            if r.returncode != 0:
                bad.append(f"chromium exit {r.returncode}")
            console = [line for line in r.stderr.splitlines() if ":CONSOLE" in line]
            bad += [f"console: {line[line.find('CONSOLE'):][:200]}" for line in console]
            m = re.search(r'<div id="pounding-measure" hidden="">(.*?)</div>', r.stdout, re.S)
            if not m or not m.group(1).strip():
                bad.append("the measuring script left nothing in the DOM")
                meas = {"figures": [], "answers": [], "resources": [], "viewport": [WIDTH, HEIGHT]}
            else:
                meas = json.loads(m.group(1).replace("&quot;", '"').replace("&amp;", "&"))
            own = "file://" + os.path.abspath(page)
            bad += [f"the page fetched {u}" for u in meas["resources"] if not u.startswith(("data:", own))]
            if os.path.exists(netlog):
                bad += [f"a request left the file: {u}" for u in page_requests(netlog)
                        if not u.startswith(("file:", "data:"))]
            else:
                bad.append("Chromium wrote no net log")
            for fig in meas["figures"]:
                if not fig["svg"] or fig["w"] <= 0 or fig["h"] <= 0:
                    bad.append(f"figure {fig['id']} has an empty bounding box ({fig['w']} x {fig['h']}, svg {fig['svg']})")
            vh = meas["viewport"][1]
            if not meas["answers"]:
                bad.append("no answer block")
            for a in meas["answers"]:
                if not (a["height"] > 0 and a["top"] >= 0 and a["bottom"] <= vh):
                    bad.append(f"the answer block ({a['top']:.0f}-{a['bottom']:.0f} px) is not within the first screen "
                               f"({vh} px)")
            for out, magic in ((png, b"\x89PNG"), (pdf, b"%PDF")):
                if not os.path.exists(out) or os.path.getsize(out) < 1000 or open(out, "rb").read(4) != magic:
                    bad.append(f"no {os.path.basename(out)} written")
            if bad:
                failures += [f"{path}: {b}" for b in bad]
            else:
                print(f"ok {name}: {len(meas['figures'])} figures drawn, answer at "
                      f"{meas['answers'][0]['top']:.0f}-{meas['answers'][0]['bottom']:.0f} px of {vh}, no console "
                      f"message, no request beyond the file; {os.path.basename(png)}, {os.path.basename(pdf)}")
    finally:
        shutil.rmtree(work, ignore_errors=True)
    for f in failures:
        print(f"FAIL: {f}")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
