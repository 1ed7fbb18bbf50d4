#!/usr/bin/python3
"""Checks an HTML page the way a person would see it, in headless Chromium with no network.

    check_page.py CHROMIUM PAGE.html SCREENSHOT.png [--min-figures N]

Fails (exit 1, naming each problem) on: a console error or uncaught exception, an image that does
not load (broken, or zero-sized), an empty plot (an <svg> without drawn marks or without size),
anything that needs the network (an http(s) URL in src/href/url(), or any resource the browser
fetched that is not a data: URI or the page itself), fewer figures than expected, or a blank
screenshot. Static checks run on the HTML first, then Chromium loads an instrumented copy (an
inline script that records errors and measures every image and plot after load, then writes the
result into the DOM, read back with --dump-dom), then takes a full-page screenshot of the page
itself. Only the standard library and matplotlib (to read the screenshot back).
"""
import argparse
import base64
import json
import os
import re
import struct
import subprocess
import sys
import tempfile

PROBE = r"""<script>
(function () {
  var problems = [];
  window.addEventListener('error', function (e) {
    var t = e.target;
    if (t && t !== window && (t.src || t.href)) problems.push('resource failed: ' + (t.src || t.href).slice(0, 80));
    else problems.push('uncaught error: ' + e.message);
  }, true);
  var origError = console.error;
  console.error = function () { problems.push('console.error: ' + Array.prototype.join.call(arguments, ' ')); origError.apply(console, arguments); };
  window.addEventListener('load', function () {
    var imgs = document.querySelectorAll('img'), svgs = document.querySelectorAll('svg');
    var figures = 0;
    imgs.forEach(function (im, i) {
      var r = im.getBoundingClientRect();
      if (!im.complete || im.naturalWidth === 0 || im.naturalHeight === 0) problems.push('broken image #' + i + ' (' + (im.alt || '') + ')');
      else if (r.width < 20 || r.height < 20) problems.push('image #' + i + ' drawn ' + r.width + ' x ' + r.height + ' px');
      else figures++;
    });
    svgs.forEach(function (s, i) {
      if (s.parentElement && s.parentElement.closest('svg')) return;
      var r = s.getBoundingClientRect();
      var marks = s.querySelectorAll('polyline, polygon, circle, path, image, rect').length;
      var drawn = s.querySelectorAll('polyline, polygon, circle, path, image').length;
      var label = s.getAttribute('aria-label') || ('svg #' + i);
      if (r.width < 50 || r.height < 50) problems.push('plot "' + label + '" drawn ' + r.width + ' x ' + r.height + ' px');
      else if (drawn === 0) problems.push('empty plot "' + label + '" (' + marks + ' marks, no data drawn)');
      else figures++;
      s.querySelectorAll('image').forEach(function (im) {
        var h = im.getAttribute('href') || '';
        if (h.indexOf('data:image/') !== 0) problems.push('plot "' + label + '" embeds a non-data image');
        var b = im.getBBox();
        if (b.width <= 0 || b.height <= 0) problems.push('plot "' + label + '" has a zero-sized image');
      });
    });
    var fetched = performance.getEntriesByType('resource').map(function (e) { return e.name; })
      .filter(function (n) { return n.indexOf('data:') !== 0; });
    fetched.forEach(function (n) { problems.push('fetched a resource: ' + n.slice(0, 100)); });
    var out = document.createElement('pre');
    out.id = 'frictal-check';
    out.textContent = JSON.stringify({problems: problems, figures: figures, height: document.documentElement.scrollHeight,
                                      width: document.documentElement.scrollWidth});
    document.body.appendChild(out);
  });
})();
</script>"""

CHROME_FLAGS = ["--headless=new", "--no-sandbox", "--disable-gpu", "--hide-scrollbars", "--no-first-run",
                "--disable-extensions", "--disable-background-networking", "--disable-sync",
                "--disable-component-update", "--disable-default-apps", "--mute-audio",
                "--host-resolver-rules=MAP * ~NOTFOUND",  # no name resolves: nothing outside can be reached
                "--proxy-server=127.0.0.1:9", "--virtual-time-budget=8000"]


def static_problems(text):
    problems = []
    stripped = text.replace('xmlns="http://www.w3.org/2000/svg"', "")
    for m in re.finditer(r"""(?:src|href)\s*=\s*["']?\s*(https?:|//|ftp:)""", stripped, re.I):
        problems.append(f"network reference at offset {m.start()}: {stripped[m.start():m.start() + 80]!r}")
    for m in re.finditer(r"url\(\s*['\"]?\s*(https?:|//)", stripped, re.I):
        problems.append(f"network url() at offset {m.start()}")
    for m in re.finditer(r"""(?:src|href)\s*=\s*["']([^"'#][^"']*)["']""", stripped, re.I):
        v = m.group(1)
        if not v.startswith("data:"):
            problems.append(f"external file referenced: {v[:80]!r}")
    # every embedded PNG decodes to a PNG with a non-zero size
    for k, m in enumerate(re.finditer(r"data:image/png;base64,([A-Za-z0-9+/=]+)", text)):
        try:
            raw = base64.b64decode(m.group(1), validate=True)
        except Exception as e:  # noqa: BLE001
            problems.append(f"embedded PNG #{k}: not base64 ({e})")
            continue
        if raw[:8] != b"\x89PNG\r\n\x1a\n" or raw[12:16] != b"IHDR":
            problems.append(f"embedded PNG #{k}: not a PNG")
            continue
        w, h = struct.unpack(">II", raw[16:24])
        if w == 0 or h == 0:
            problems.append(f"embedded PNG #{k}: {w} x {h} pixels")
    if "<svg" not in text and "<img" not in text:
        problems.append("no figure at all")
    return problems


def chromium(chrome, args, timeout=90):
    return subprocess.run([chrome, *CHROME_FLAGS, *args], capture_output=True, text=True, timeout=timeout)


def main(argv):
    ap = argparse.ArgumentParser()
    ap.add_argument("chromium")
    ap.add_argument("page")
    ap.add_argument("screenshot")
    ap.add_argument("--min-figures", type=int, default=1)
    ap.add_argument("--width", type=int, default=1200)
    a = ap.parse_args(argv)
    text = open(a.page, encoding="utf-8").read()
    problems = static_problems(text)

    # Instrumented copy: the probe first in <head> so that it sees every error.
    with tempfile.TemporaryDirectory() as tmp:
        probe_page = os.path.join(tmp, "probe.html")
        inst = re.sub(r"<head>", "<head>" + PROBE, text, count=1) if "<head>" in text else PROBE + text
        open(probe_page, "w", encoding="utf-8").write(inst)
        r = chromium(a.chromium, [f"--user-data-dir={tmp}/profile", f"--window-size={a.width},1000", "--dump-dom",
                                  "file://" + os.path.abspath(probe_page)])
        m = re.search(r'<pre id="frictal-check">(.*?)</pre>', r.stdout, re.S)
        if r.returncode != 0 or not m:
            problems.append(f"chromium did not render the page (exit {r.returncode}): {r.stderr[-600:]}")
            result = {"problems": [], "figures": 0, "height": 2000, "width": a.width}
        else:
            result = json.loads(m.group(1).replace("&quot;", '"').replace("&lt;", "<").replace("&gt;", ">")
                                .replace("&amp;", "&"))
        problems += result["problems"]
        if result["figures"] < a.min_figures:
            problems.append(f"{result['figures']} figures drawn, expected at least {a.min_figures}")
        if result["width"] > a.width + 5:
            problems.append(f"the page is {result['width']} px wide in a {a.width} px window (horizontal scrolling)")
        # Screenshot of the page itself, as tall as the page.
        height = max(600, min(int(result["height"]) + 20, 16000))
        shot = os.path.abspath(a.screenshot)
        os.makedirs(os.path.dirname(shot), exist_ok=True)
        if os.path.exists(shot):
            os.remove(shot)
        r = chromium(a.chromium, [f"--user-data-dir={tmp}/profile2", f"--window-size={a.width},{height}",
                                  f"--screenshot={shot}", "file://" + os.path.abspath(a.page)])
    if not os.path.exists(shot) or os.path.getsize(shot) == 0:
        problems.append(f"no screenshot written (chromium exit {r.returncode}): {r.stderr[-400:]}")
    else:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.image as mpimg
        px = mpimg.imread(shot)
        if px.std() < 0.01:
            problems.append(f"the screenshot {shot} is blank")
    for p in problems:
        print(f"check_page: {a.page}: {p}", file=sys.stderr)
    print(f"check_page: {a.page}: {result['figures']} figures, {len(problems)} problems; screenshot {a.screenshot}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
