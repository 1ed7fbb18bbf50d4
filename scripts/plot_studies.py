#!/usr/bin/python3
"""Draws the figures that study files declare, from their stores (SQLite, docs/studies.md).

    scripts/plot_studies.py OUTDIR (--kinds KINDS.json | --frictal BIN) --study STUDY.toml STORE.sqlite ...

Nothing here knows a task kind or a figure of the paper. A study file's [[figure]] entries name
the file, title and panels; each panel names plot views by id. What a part contributes to a view
(columns, axes, labels, units, grouping, markers) is data declared by its task kind in the
registry, exported by `frictal study kinds --json` (save it with the stores to plot a store copied
from a cluster without a frictal build). Only the standard library, numpy and matplotlib.
"""
import argparse
import collections
import json
import math
import re
import sqlite3
import string
import subprocess
import sys
import tomllib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


class _Fmt(string.Formatter):
    """str.format with reals printed shortest (%g) unless a format is given."""

    def format_field(self, value, spec):
        if spec == "" and isinstance(value, float):
            return format(value, "g")
        return super().format_field(value, spec)


def fmt(template, values):
    try:
        return _Fmt().vformat(template, (), collections.defaultdict(lambda: "?", values))
    except (ValueError, IndexError, KeyError):
        return template


class Store:
    """The done tasks of a store: part, kind, params, scalars; arrays read on demand."""

    def __init__(self, path):
        self.path = path
        self.con = sqlite3.connect(f"file:{path}?mode=ro", uri=True)
        self.rows = []
        for tid, part, kind, params, scalars in self.con.execute(
                "SELECT task_id, part, kind, params, scalars FROM tasks WHERE status = 'done' ORDER BY task_id"):
            s = {k: (math.nan if v is None else v) for k, v in json.loads(scalars or "{}").items()}
            self.rows.append({"id": tid, "part": part, "kind": kind, "params": json.loads(params), "scalars": s})
        self.parts = list(dict.fromkeys((r["part"], r["kind"]) for r in self.rows))
        self._arrays = {}

    def arrays(self, task_id):
        if task_id not in self._arrays:
            self._arrays[task_id] = {
                name: np.array([np.nan if v is None else v for v in json.loads(js)], dtype=float)
                for name, js in self.con.execute("SELECT name, json FROM arrays WHERE task_id = ?", (task_id,))}
        return self._arrays[task_id]


def value(row, column):
    if column in row["params"]:
        return row["params"][column]
    return row["scalars"].get(column)


def matched(store, row, column, match):
    """A column of the row, or of another task with the same values of the `match` parameters."""
    v = value(row, column)
    if v is not None or not match:
        return v
    key = [row["params"].get(m) for m in match]
    for other in store.rows:
        if [other["params"].get(m) for m in match] == key:
            w = value(other, column)
            if w is not None:
                return w
    return None


_CMP = re.compile(r"^\s*(<=|>=|<|>|==)\s*(-?[0-9.eE+-]+)\s*$")


def select(rows, where):
    """Rows whose parameters satisfy `where` (number or list: equal; "<= x" etc.; "max"/"min")."""
    resolved = {}
    for name, cond in (where or {}).items():
        have = [r for r in rows if name in r["params"]]
        vals = [r["params"][name] for r in have]
        if cond in ("max", "min"):
            target = (max if cond == "max" else min)(vals) if vals else None
            rows = [r for r in have if r["params"][name] == target]
            resolved[name] = target
        elif isinstance(cond, str) and _CMP.match(cond):
            op, x = _CMP.match(cond).groups()
            x = float(x)
            test = {"<=": lambda v: v <= x + 1e-12, ">=": lambda v: v >= x - 1e-12, "<": lambda v: v < x,
                    ">": lambda v: v > x, "==": lambda v: abs(v - x) <= 1e-12}[op]
            rows = [r for r in have if test(r["params"][name])]
            resolved[name] = cond
        else:
            allowed = cond if isinstance(cond, list) else [cond]
            rows = [r for r in have if r["params"][name] in allowed]
            resolved[name] = cond
    return rows, resolved


def style(view, color, n_series_points):
    kw = {"color": color}
    marker = view["marker"]
    kw["linestyle"] = "-" if view["line"] else "none"
    if view.get("line_width", 0) > 0:
        kw["lw"] = view["line_width"]
    if marker:
        kw["marker"] = marker
        if view.get("marker_size", 0) > 0:
            kw["ms"] = view["marker_size"]
        if view["open"]:
            kw["mfc"] = "none"
    return kw


def color_of(view, series_value):
    if view["color"]:
        return view["color"]
    if isinstance(series_value, int) and not isinstance(series_value, bool):
        return f"C{series_value}"
    return None


def divided(store, row, axis, values):
    if axis["divide_by"]:
        d = matched(store, row, axis["divide_by"], [])
        if d:
            return values / d
    return values


def draw(ax, store, view, rows, arrays_of_kind):
    """Draws one view of one part's rows; returns the rows drawn."""
    x_ax, y_ax = view["x"], view["y"]
    drawn = []
    if x_ax["column"] in arrays_of_kind and y_ax["column"] in arrays_of_kind:  # one curve per task
        for row in rows:
            a = store.arrays(row["id"])
            if x_ax["column"] not in a or y_ax["column"] not in a:
                continue
            x = divided(store, row, x_ax, a[x_ax["column"]])
            y = divided(store, row, y_ax, a[y_ax["column"]])
            label = fmt(view["label"], {**row["params"], **row["scalars"]})
            ax.plot(x, y, label=label, **style(view, color_of(view, None), len(x)))
            drawn.append(row)
        return drawn
    groups = collections.OrderedDict()
    for row in rows:
        x = matched(store, row, x_ax["column"], view["match"])
        y = matched(store, row, y_ax["column"], view["match"])
        if x is None or y is None:
            continue
        key = row["id"] if view["series"] == "task" else row["params"].get(view["series"]) if view["series"] else None
        groups.setdefault(key, []).append((row, x, y))
    for key in sorted(groups, key=lambda k: (k is None, k)):
        pts = groups[key]
        if view["average_over"]:
            acc = collections.OrderedDict()
            for row, x, y in pts:
                acc.setdefault(x, []).append(y)
            xy = sorted((x, float(np.mean(ys))) for x, ys in acc.items())
        else:
            xy = sorted((x, y) for _, x, y in pts)
        row0 = pts[0][0]
        xs = divided(store, row0, x_ax, np.array([p[0] for p in xy], dtype=float))
        ys = divided(store, row0, y_ax, np.array([p[1] for p in xy], dtype=float))
        label = fmt(view["label"], {**row0["params"], **row0["scalars"]})
        ax.plot(xs, ys, label=label, **style(view, color_of(view, key), len(xs)))
        drawn.extend(p[0] for p in pts)
    return drawn


def reference(ax, store, view, drawn, arrays_of_kind):
    ref = view["reference"]
    if not ref or not drawn:
        return
    label = view["reference_label"]
    if ref == "identity":
        xs = [matched(store, r, view["x"]["column"], view["match"]) for r in drawn]
        lim = [0, max([x for x in xs if x is not None] + [45])]
        ax.plot(lim, lim, "k-", lw=0.8, label=fmt(label, {}))
    elif ref.startswith("power:"):  # y ~ x^(1 - column) through the last curve's largest x
        col = ref.split(":", 1)[1]
        row = drawn[-1]
        if view["x"]["column"] in arrays_of_kind:
            a = store.arrays(row["id"])
            x = divided(store, row, view["x"], a[view["x"]["column"]])
            y = divided(store, row, view["y"], a[view["y"]["column"]])
        else:
            return
        k = int(np.argmax(x))
        d = value(row, col)
        ax.plot(x, y[k] * (x / x[k]) ** (1 - d), "k--", lw=1, label=fmt(label, {**row["params"], **row["scalars"]}))


def figure(store, kinds, spec, outdir):
    panels = spec.get("panel") or [spec]
    grid = spec.get("grid") or [1, len(panels)]
    size = spec.get("size") or [6 * grid[1] if grid[1] > 1 else 6, 4.5 * grid[0] if grid[0] > 1 else 4.5]
    fig, axes = plt.subplots(grid[0], grid[1], figsize=tuple(size), squeeze=False)
    views_of = {name: {v["id"]: v for v in k["plots"]} for name, k in kinds.items()}
    arrays_of = {name: {o["name"] for o in k["outputs"] if o["array"]} for name, k in kinds.items()}
    many = len(panels) > 1
    for ax, panel in zip(axes.ravel(), panels):
        rows_all, resolved = select(store.rows, panel.get("where"))
        first = None
        for vid in panel["views"]:
            for part, kind in store.parts:
                if panel.get("parts") and part not in panel["parts"]:
                    continue
                view = views_of.get(kind, {}).get(vid)
                if not view:
                    continue
                first = first or view
                rows = [r for r in rows_all if r["part"] == part]
                drawn = draw(ax, store, view, rows, arrays_of.get(kind, set()))
                reference(ax, store, view, drawn, arrays_of.get(kind, set()))
        if first is None:
            raise KeyError(f"no part of {store.path} has a view among {panel['views']}")
        for axis, set_label, set_scale, set_lim in (("x", ax.set_xlabel, ax.set_xscale, ax.set_xlim),
                                                     ("y", ax.set_ylabel, ax.set_yscale, ax.set_ylim)):
            a = first[axis]
            set_label(a["label"])
            if a["log"]:
                set_scale("log")
            if a["min"] is not None or a["max"] is not None:
                set_lim(a["min"], a["max"])
        title = panel.get("title") or (None if many else spec.get("title"))
        if title:
            ax.set_title(fmt(title, resolved), **({"fontsize": 9} if grid[0] * grid[1] > 2 else {}))
        ax.legend(fontsize=6 if grid[0] * grid[1] > 2 else 7 if many else 8)
    if many and spec.get("title"):
        fig.suptitle(spec["title"])
    fig.tight_layout()
    path = f"{outdir}/{spec['file']}.png"
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("outdir")
    ap.add_argument("--kinds", help="output of `frictal study kinds --json`")
    ap.add_argument("--frictal", help="a frictal executable to ask for the kinds instead")
    ap.add_argument("--study", nargs=2, action="append", default=[], metavar=("STUDY.toml", "STORE.sqlite"))
    a = ap.parse_args(argv)
    if a.kinds:
        with open(a.kinds, encoding="utf-8") as f:
            kinds = json.load(f)
    elif a.frictal:
        kinds = json.loads(subprocess.run([a.frictal, "study", "kinds", "--json"], check=True, capture_output=True,
                                          text=True).stdout)
    else:
        ap.error("give --kinds FILE or --frictal BIN")
    kinds = {k["name"]: k for k in kinds["kinds"]}
    done = []
    for toml_path, store_path in a.study:
        try:
            with open(toml_path, "rb") as f:
                figures = tomllib.load(f).get("figure", [])
            if not figures:
                continue
            store = Store(store_path)
            for spec in figures:
                done.append(figure(store, kinds, spec, a.outdir))
        except (OSError, sqlite3.Error, KeyError, ValueError, tomllib.TOMLDecodeError) as e:
            print(f"plot_studies: {toml_path}: cannot plot {store_path}: {e}", file=sys.stderr)
            return 2
    print("plot_studies: wrote " + ", ".join(done))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
