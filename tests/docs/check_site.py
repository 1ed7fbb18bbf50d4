#!/usr/bin/python3
"""Checks the built documentation site the way a reader meets it (CTest docs.check).

    check_site.py HTML_DIR SOURCE_DIR [--chromium PATH] [--module-dir BUILD/python]

Fails (exit 1, naming each problem) on:
  - a broken internal link: an href or src that names a file the site does not have, or an
    #anchor that the target page does not define;
  - a missing or empty image;
  - anything loaded from the network (an http(s) src, or a resource Chromium fetched that is not
    a file of the site);
  - a notebook of SOURCE_DIR/docs/site/tutorials that is not on the site, or whose executed copy
    has a cell that raised or a code cell that did not run;
  - a page that Chromium (headless, no network) opens with a console error, an uncaught
    exception, a failed resource, a broken image, or math that MathJax did not typeset;
  - with --module-dir (the built Python package): a public name of `frictal` or `frictal.plots`
    that the Python API page does not document.
Each page is loaded as an instrumented copy beside it (so relative resources resolve), with a
script that records errors and writes them into the DOM, read back with --dump-dom.
"""
import argparse
import concurrent.futures
import glob
import html.parser
import json
import os
import re
import subprocess
import sys
import tempfile
import urllib.parse

CHROME_FLAGS = ["--headless=new", "--no-sandbox", "--disable-gpu", "--hide-scrollbars", "--no-first-run",
                "--disable-extensions", "--disable-background-networking", "--disable-sync",
                "--disable-component-update", "--disable-default-apps", "--mute-audio",
                "--allow-file-access-from-files",
                "--host-resolver-rules=MAP * ~NOTFOUND",  # no name resolves: nothing outside can be reached
                "--proxy-server=127.0.0.1:9", "--virtual-time-budget=10000"]

PROBE = r"""<script>
(function () {
  var problems = [];
  window.addEventListener('error', function (e) {
    var t = e.target;
    if (t && t !== window && (t.src || t.href)) problems.push('resource failed: ' + (t.src || t.href));
    else problems.push('uncaught error: ' + e.message + ' (' + (e.filename || '') + ':' + (e.lineno || '') + ')');
  }, true);
  window.addEventListener('unhandledrejection', function (e) { problems.push('unhandled rejection: ' + e.reason); });
  var origError = console.error;
  console.error = function () {
    problems.push('console.error: ' + Array.prototype.join.call(arguments, ' '));
    origError.apply(console, arguments);
  };
  window.addEventListener('load', function () {
    setTimeout(function () {
      document.querySelectorAll('img').forEach(function (im, i) {
        if (!im.complete || im.naturalWidth === 0 || im.naturalHeight === 0)
          problems.push('broken image #' + i + ' ' + (im.getAttribute('src') || ''));
      });
      var math = document.querySelectorAll('span.math, div.math').length;
      var typeset = document.querySelectorAll('.MathJax_CHTML, .MathJax_Display, .MathJax, mjx-container').length;
      if (math > 0 && typeset === 0) problems.push(math + ' math elements, none typeset by MathJax');
      if (document.querySelector('.MathJax_Error, merror')) problems.push('MathJax reports a math error');
      performance.getEntriesByType('resource').forEach(function (e) {
        if (e.name.indexOf('file:') !== 0 && e.name.indexOf('data:') !== 0) problems.push('network request: ' + e.name);
      });
      var pre = document.createElement('pre');
      pre.id = 'frictal-docs-check';
      pre.textContent = JSON.stringify({problems: problems, math: math, typeset: typeset});
      document.body.appendChild(pre);
    }, 4000);
  });
})();
</script>"""


class Links(html.parser.HTMLParser):
    def __init__(self):
        super().__init__()
        self.refs, self.ids, self.imgs = [], set(), []

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        for key in ("id", "name"):
            if a.get(key):
                self.ids.add(a[key])
        if tag == "a" and a.get("href"):
            self.refs.append(("href", a["href"]))
        if tag in ("img", "script", "source") and a.get("src"):
            self.refs.append(("src", a["src"]))
            if tag == "img":
                self.imgs.append(a["src"])
        if tag == "link" and a.get("href") and a.get("rel") and "stylesheet" in a.get("rel"):
            self.refs.append(("src", a["href"]))


def pages_of(site):
    out = []
    for p in sorted(glob.glob(os.path.join(site, "**", "*.html"), recursive=True)):
        rel = os.path.relpath(p, site)
        if rel.split(os.sep)[0] in ("_static", "_sources", "_downloads", "_images") or "/.probe-" in "/" + rel:
            continue
        out.append(p)
    return out


def static_problems(site, pages):
    parsed = {}
    for p in pages:
        parser = Links()
        parser.feed(open(p, encoding="utf-8").read())
        parsed[os.path.abspath(p)] = parser
    problems = []
    for p, parser in parsed.items():
        rel = os.path.relpath(p, site)
        for kind, url in parser.refs:
            u = urllib.parse.urlparse(url)
            if u.scheme in ("http", "https"):
                if kind == "src":
                    problems.append(f"{rel}: loads {url} from the network")
                continue
            if u.scheme in ("mailto", "javascript", "data") or url.startswith("//"):
                continue
            target = os.path.abspath(os.path.join(os.path.dirname(p), urllib.parse.unquote(u.path))) if u.path else p
            if not os.path.exists(target):
                problems.append(f"{rel}: broken link {url} (no {os.path.relpath(target, site)})")
                continue
            if os.path.isdir(target):
                target = os.path.join(target, "index.html")
            if u.fragment and target.endswith(".html"):
                if target not in parsed:  # a page outside the checked set (e.g. under _static)
                    parsed_target = Links()
                    parsed_target.feed(open(target, encoding="utf-8").read())
                    ids = parsed_target.ids
                else:
                    ids = parsed[target].ids
                if urllib.parse.unquote(u.fragment) not in ids:
                    problems.append(f"{rel}: broken anchor {url} (no id '{u.fragment}' in "
                                    f"{os.path.relpath(target, site)})")
        for src in parser.imgs:
            if src.startswith("data:"):
                continue
            f = os.path.join(os.path.dirname(p), urllib.parse.unquote(urllib.parse.urlparse(src).path))
            if os.path.exists(f) and os.path.getsize(f) == 0:
                problems.append(f"{rel}: empty image {src}")
    return problems


def notebook_problems(site, source):
    problems = []
    notebooks = sorted(glob.glob(os.path.join(source, "docs", "site", "tutorials", "*.ipynb")))
    if not notebooks:
        problems.append("no tutorial notebooks found in docs/site/tutorials")
    for nb in notebooks:
        name = os.path.splitext(os.path.basename(nb))[0]
        page = os.path.join(site, "tutorials", name + ".html")
        executed = os.path.join(site, "tutorials", name + ".ipynb")
        if not os.path.exists(page):
            problems.append(f"tutorial {name}: no page tutorials/{name}.html")
            continue
        if not os.path.exists(executed):
            problems.append(f"tutorial {name}: the executed notebook is not on the site")
            continue
        cells = json.load(open(executed, encoding="utf-8"))["cells"]
        code = [c for c in cells if c["cell_type"] == "code" and "".join(c["source"]).strip()]
        for i, c in enumerate(code):
            if c.get("execution_count") is None:
                problems.append(f"tutorial {name}: code cell {i + 1} did not run")
            for o in c.get("outputs", []):
                if o.get("output_type") == "error":
                    problems.append(f"tutorial {name}: code cell {i + 1} raised {o.get('ename')}: {o.get('evalue')}")
        if not any(o.get("output_type") == "display_data" and "image/png" in o.get("data", {})
                   for c in code for o in c.get("outputs", [])):
            problems.append(f"tutorial {name}: no figure in its outputs")
    return problems


def python_api_problems(site, module_dir):
    """Every public name of the package has its entry on the Python API page."""
    sys.path.insert(0, module_dir)
    import frictal
    import frictal.plots
    text = open(os.path.join(site, "reference", "python.html"), encoding="utf-8").read()
    ids = set(re.findall(r'id="(frictal\.[\w.]+)"', text))
    names = [f"frictal.{n}" for n in frictal.__all__]
    names += [f"frictal.plots.{n}" for n in dir(frictal.plots)
              if not n.startswith("_") and callable(getattr(frictal.plots, n))
              and getattr(getattr(frictal.plots, n), "__module__", "") == "frictal.plots"]
    return [f"reference/python.html: {n} is not documented" for n in names if n not in ids]


def browser_problems(chrome, site, page):
    rel = os.path.relpath(page, site)
    text = open(page, encoding="utf-8").read()
    probe = os.path.join(os.path.dirname(page), ".probe-" + os.path.basename(page))
    inst = re.sub(r"<head>", "<head>" + PROBE, text, count=1) if "<head>" in text else PROBE + text
    with open(probe, "w", encoding="utf-8") as f:
        f.write(inst)
    try:
        with tempfile.TemporaryDirectory() as tmp:
            r = subprocess.run([chrome, *CHROME_FLAGS, f"--user-data-dir={tmp}", "--window-size=1280,1000",
                                "--dump-dom", "file://" + probe], capture_output=True, text=True, timeout=120)
    finally:
        os.remove(probe)
    m = re.search(r'<pre id="frictal-docs-check">(.*?)</pre>', r.stdout, re.S)
    if r.returncode != 0 or not m:
        return [f"{rel}: chromium did not render the page (exit {r.returncode}): {r.stderr[-400:]}"]
    result = json.loads(m.group(1).replace("&quot;", '"').replace("&lt;", "<").replace("&gt;", ">")
                        .replace("&amp;", "&"))
    return [f"{rel}: {p.replace('.probe-', '')}" for p in result["problems"]]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("site")
    ap.add_argument("source")
    ap.add_argument("--chromium", default="chromium")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--module-dir", help="the built Python package's folder: check the Python API's coverage")
    a = ap.parse_args()
    site = os.path.abspath(a.site)
    if not os.path.exists(os.path.join(site, "index.html")):
        print(f"check_site: {site}/index.html does not exist (the docs.build test makes it)", file=sys.stderr)
        return 1
    pages = pages_of(site)
    problems = static_problems(site, pages) + notebook_problems(site, a.source)
    if a.module_dir:
        problems += python_api_problems(site, a.module_dir)
    with concurrent.futures.ThreadPoolExecutor(max_workers=a.jobs) as pool:
        for found in pool.map(lambda p: browser_problems(a.chromium, site, p), pages):
            problems += found
    for p in problems:
        print(f"check_site: {p}", file=sys.stderr)
    print(f"check_site: {len(pages)} pages opened in Chromium, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
