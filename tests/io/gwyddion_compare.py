#!/usr/bin/env python3
"""Every instrument file that Gwyddion reads: frictal's numbers against Gwyddion's own.

Gwyddion's side is computed here, independently of frictal's C++ backend: its libraries are
loaded with ctypes, each file is opened with gwy_file_load() and the statistics come from
Gwyddion's own functions (gwy_data_field_area_get_stats_mask with the file's mask excluded,
gwy_data_field_area_get_min_max_mask, gwy_data_field_get_xreal, ...). frictal's side is the
CLI (`frictal info --json`, `frictal stats --json`), whichever reader frictal uses for the file
(native or its Gwyddion backend). Compared per file: grid, physical size n dx (Gwyddion's
xreal/yreal), number of valid points, mean, Sq, Sa, Ssk, Sku (Gwyddion's kurtosis is the excess
kurtosis: Sku - 3), Sz = max - min, and Sdq (gwy_data_field_area_get_surface_slope_mask) where the
two definitions coincide (square grids without masked points).

Usage: gwyddion_compare.py FRICTAL DATA_DIR [--markdown OUT.md]
Exit status 77 (CTest: skipped) where Gwyddion's libraries or file modules are not installed.
"""
import ctypes
import json
import math
import os
import re
import subprocess
import sys

SKIP = 77

# file (in DATA_DIR), frictal's --channel ("" = its default) and Gwyddion's channel id (None: the
# first image whose lateral and value units are both metres, chosen here from Gwyddion's units).
FILES = [
    ("instruments/al3d-1.al3d", "", None),
    ("instruments/bcrf-1.bcrf", "", None),
    ("instruments/di-1.di", "", None),
    ("instruments/di-1.di", "1", 1),
    ("instruments/di-3.di", "", None),
    ("instruments/di-3.di", "Height", 3),
    ("instruments/example_ps.tiff", "", None),
    ("instruments/frt-2.frt", "", None),
    ("instruments/metropro-1.dat", "", None),
    ("instruments/mi-1.mi", "", None),
    ("instruments/nid-1.nid", "", None),
    ("instruments/opd-1.opd", "", None),
    ("instruments/plu-1.plu", "", None),
    ("instruments/stp-1.stp", "", None),
    ("instruments/top-1.top", "", None),
    ("instruments/sur-3.sur", "", None),
    ("instruments/spot_1-1000nm.ibw", "", None),
    ("instruments/sample_0.jpk-qi-image", "", None),
    ("instruments/sdf-1.sdf", "", None),
    ("instruments/gwyfile-test.gwy", "", 0),
    ("instruments/10x10-one_channel_without_name.ibw", "", 0),
    # x, y, z points on a grid: frictal's native reader against Gwyddion's rawxyz (which
    # regularises the points; on a complete grid it keeps the values).
    ("instruments/xyz-1.txt", "", 0),
    ("instruments/xyz-1-different-order.txt", "", 0),
    ("x3p/pyramid.x3p", "", None),
    ("x3p/x3p-2.x3p", "", None),
    ("x3p/ISO5436-sample4_bin.x3p", "", None),
]
# Curves (graphs): frictal's profile against Gwyddion's curve.
CURVES = [("instruments/opdx-3.opdx", "")]

# Relative tolerance on every compared number. Both read the same values from the file; what
# differs is the summation order (and for the x3p files the two independent readers).
RTOL = 1e-9


class Gwy:
    def __init__(self, moddir):
        self.libs = []
        for n in ["libgwyddion2.so.0", "libgwyprocess2.so.0", "libgwydraw2.so.0", "libgwydgets2.so.0",
                  "libgwymodule2.so.0", "libgwyapp2.so.0"]:
            self.libs.append(ctypes.CDLL(n, mode=ctypes.RTLD_GLOBAL))
        vp, d, i, cp, u32 = ctypes.c_void_p, ctypes.c_double, ctypes.c_int, ctypes.c_char_p, ctypes.c_uint32
        pd = ctypes.POINTER(d)
        self.f("gwy_type_init", None)()
        self.f("gwy_draw_type_init", None)()
        self.f("gwy_process_type_init", None)()
        gtype = self.f("gwy_gradient_get_type", ctypes.c_ulong)()
        self.f("gwy_resource_class_load", None, vp)(self.f("g_type_class_ref", vp, ctypes.c_ulong)(gtype))
        if not os.path.isdir(os.path.join(moddir, "file")):
            raise OSError("no Gwyddion file modules in " + moddir)
        paths = (cp * 2)(os.path.join(moddir, "file").encode(), None)
        self.f("gwy_module_register_modules", None, ctypes.POINTER(cp))(paths)
        self.load = self.f("gwy_file_load", vp, cp, i, vp)
        self.detect = self.f("gwy_file_detect", cp, cp, i, i)
        self.keys = self.f("gwy_container_keys_by_name", ctypes.POINTER(cp), vp)
        self.n_items = self.f("gwy_container_get_n_items", ctypes.c_uint, vp)
        self.quark = self.f("g_quark_from_string", u32, cp)
        self.gis_object = self.f("gwy_container_gis_object", i, vp, u32, ctypes.POINTER(vp))
        self.gis_string = self.f("gwy_container_gis_string", i, vp, u32, ctypes.POINTER(cp))
        self.xres = self.f("gwy_data_field_get_xres", i, vp)
        self.yres = self.f("gwy_data_field_get_yres", i, vp)
        self.xreal = self.f("gwy_data_field_get_xreal", d, vp)
        self.yreal = self.f("gwy_data_field_get_yreal", d, vp)
        self.unit_xy = self.f("gwy_data_field_get_si_unit_xy", vp, vp)
        self.unit_z = self.f("gwy_data_field_get_si_unit_z", vp, vp)
        self.unit_equal = self.f("gwy_si_unit_equal_string", i, vp, cp)
        self.stats = self.f("gwy_data_field_area_get_stats_mask", None, vp, vp, i, i, i, i, i, pd, pd, pd, pd, pd)
        self.slope = self.f("gwy_data_field_area_get_surface_slope_mask", d, vp, vp, i, i, i, i, i)
        self.minmax = self.f("gwy_data_field_area_get_min_max_mask", None, vp, vp, i, i, i, i, i, pd, pd)
        self.count = self.f("gwy_data_field_area_count_in_range", None, vp, vp, i, i, i, i, d, d,
                            ctypes.POINTER(i), ctypes.POINTER(i))
        self.n_curves = self.f("gwy_graph_model_get_n_curves", i, vp)
        self.curve = self.f("gwy_graph_model_get_curve", vp, vp, i)
        self.ndata = self.f("gwy_graph_curve_model_get_ndata", i, vp)
        self.xdata = self.f("gwy_graph_curve_model_get_xdata", pd, vp)
        self.ydata = self.f("gwy_graph_curve_model_get_ydata", pd, vp)
        self.unref = self.f("g_object_unref", None, vp)

    def f(self, name, res, *args):
        for lib in self.libs:
            fn = getattr(lib, name, None)
            if fn is not None:
                fn.restype = res
                fn.argtypes = list(args)
                return fn
        raise OSError("Gwyddion's libraries lack " + name)

    def obj(self, c, key):
        o = ctypes.c_void_p()
        return o if self.gis_object(c, self.quark(key.encode()), ctypes.byref(o)) and o.value else None

    def image(self, path, want):
        """Gwyddion's numbers for one image channel of `path`."""
        c = self.load(path.encode(), 1, None)  # GWY_RUN_NONINTERACTIVE
        if not c:
            return None
        module = self.detect(path.encode(), 0, 2)
        k = self.keys(c)
        ids = sorted(int(m.group(1)) for m in (re.fullmatch(rb"/(\d+)/data", k[j]) for j in range(self.n_items(c)))
                     if m)
        if want is None:
            want = next((n for n in ids if self.unit_equal(self.unit_xy(self.obj(c, "/%d/data" % n)), b"m")
                         and self.unit_equal(self.unit_z(self.obj(c, "/%d/data" % n)), b"m")), None)
        if want is None:
            self.unref(c)
            return None
        field = self.obj(c, "/%d/data" % want)
        mask = self.obj(c, "/%d/mask" % want)
        title = ctypes.c_char_p()
        self.gis_string(c, self.quark(b"/%d/data/title" % want), ctypes.byref(title))
        nx, ny = self.xres(field), self.yres(field)
        v = [ctypes.c_double() for _ in range(7)]
        mode = 0 if mask else 2  # GWY_MASK_EXCLUDE, GWY_MASK_IGNORE
        self.stats(field, mask, mode, 0, 0, nx, ny, *[ctypes.byref(x) for x in v[:5]])
        self.minmax(field, mask, mode, 0, 0, nx, ny, ctypes.byref(v[5]), ctypes.byref(v[6]))
        masked = 0
        if mask:
            below, above = ctypes.c_int(), ctypes.c_int()
            # Points of the mask above 0.5: the ones Gwyddion's statistics exclude.
            self.count(mask, None, 0, 0, nx, ny, 0.5, 0.5, ctypes.byref(below), ctypes.byref(above))
            masked = above.value
        r = dict(module=module.decode() if module else "", id=want, title=title.value.decode("utf-8", "replace")
                 if title.value else "", nx=nx, ny=ny, sx=self.xreal(field), sy=self.yreal(field),
                 valid=nx * ny - masked, mean=v[0].value, Sa=v[1].value, Sq=v[2].value, Ssk=v[3].value,
                 Sku_excess=v[4].value, Sz=v[6].value - v[5].value,
                 Sdq=self.slope(field, mask, mode, 0, 0, nx, ny))
        self.unref(c)
        return r

    def curve_data(self, path):
        c = self.load(path.encode(), 1, None)
        if not c:
            return None
        k = self.keys(c)
        graphs = sorted(k[j].decode() for j in range(self.n_items(c)) if re.fullmatch(rb"/0/graph/graph/\d+", k[j]))
        if not graphs:
            self.unref(c)
            return None
        g = self.obj(c, graphs[0])
        cm = self.curve(g, 0)
        n = self.ndata(cm)
        x, y = self.xdata(cm), self.ydata(cm)
        r = dict(module=self.detect(path.encode(), 0, 2).decode(), n=n, x=[x[k] for k in range(n)],
                 y=[y[k] for k in range(n)])
        self.unref(c)
        return r


def frictal_json(exe, args):
    p = subprocess.run([exe] + args + ["--json"], capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError(" ".join(args) + ": " + p.stderr.strip())
    return json.loads(p.stdout)


def rel(a, b):
    return abs(a - b) / max(abs(b), 1e-300)


def main():
    if len(sys.argv) < 3:
        print(__doc__)
        return 2
    exe, data = sys.argv[1], sys.argv[2]
    out_md = sys.argv[sys.argv.index("--markdown") + 1] if "--markdown" in sys.argv else None
    moddir = os.environ.get("FRICTAL_GWYDDION_MODULE_DIR", "/usr/lib/x86_64-linux-gnu/gwyddion/modules")
    try:
        gwy = Gwy(moddir)
    except OSError as e:
        print("SKIP: Gwyddion is not installed (Debian packages libgwyddion2-0 and gwyddion):", e)
        return SKIP
    probe = subprocess.run([exe, "info", os.path.join(data, "instruments/sur-3.sur")], capture_output=True, text=True)
    if "without the Gwyddion backend" in probe.stderr:
        print("SKIP: this frictal was built without the Gwyddion backend:", probe.stderr.strip())
        return SKIP
    failures = []
    rows = []
    for rel_path, chan, gid in FILES:
        path = os.path.join(data, rel_path)
        g = gwy.image(path, gid)
        if g is None:
            failures.append(f"{rel_path}: Gwyddion does not load it")
            continue
        extra = ["--channel", chan] if chan else []
        info = frictal_json(exe, ["info", path] + extra)
        # Gwyddion's statistics are of the heights as read: --detrend none (frictal's default removes a plane).
        st = frictal_json(exe, ["stats", path, "--detrend", "none"] + extra)
        fname = info["channels"][info["channel"]]["name"]
        # Through Gwyddion, frictal must have read the channel whose numbers Gwyddion gives here
        # (native readers name their one channel after the format).
        if info["reader"].startswith("gwyddion:") and fname != g["title"] and \
                not (g["title"] == "" and fname.startswith("channel")):
            failures.append(f"{rel_path}: frictal read channel '{fname}', Gwyddion's is '{g['title']}'")
        checks = [("nx", st["nx"], g["nx"], 0), ("ny", st["ny"], g["ny"], 0),
                  ("valid", st["valid_points"], g["valid"], 0),
                  ("size x", st["physical_size_x_m"], g["sx"], RTOL), ("size y", st["physical_size_y_m"], g["sy"], RTOL),
                  ("mean", st["mean_height_m"], g["mean"], RTOL * max(1, abs(g["Sq"] / g["mean"]) if g["mean"] else 1)),
                  ("Sq", st["Sq_m"], g["Sq"], RTOL), ("Sa", st["Sa_m"], g["Sa"], RTOL),
                  ("Ssk", st["Ssk"], g["Ssk"], RTOL * 100), ("Sku-3", st["Sku"] - 3, g["Sku_excess"], RTOL * 100),
                  ("Sz", st["Sz_m"], g["Sz"], RTOL)]
        # Sdq: Gwyddion pools the squared slopes of both directions over all (nx-1) ny + nx (ny-1)
        # pairs, sqrt(2 (Sh/dx^2 + Sv/dy^2) / (nh + nv)); frictal averages each direction over its
        # own pairs, sqrt(Sh/(nh dx^2) + Sv/(nv dy^2)) (docs/analysis.md). The two are the same
        # number where nh = nv: square grids without masked points. Compared there; elsewhere the
        # difference is reported (docs/io.md).
        sdq_same_definition = g["nx"] == g["ny"] and g["valid"] == g["nx"] * g["ny"]
        if sdq_same_definition:
            checks.append(("Sdq", st["Sdq"], g["Sdq"], RTOL))
        g["Sdq_rel"] = rel(st["Sdq"], g["Sdq"])
        g["Sdq_compared"] = sdq_same_definition
        worst = 0.0
        for name, a, b, tol in checks:
            # Unitless channels: frictal reads them in metres, as Gwyddion's numbers are.
            r = rel(a, b) if b != 0 else abs(a)
            if name == "mean":
                r = abs(a - b) / g["Sq"] if g["Sq"] else abs(a - b)  # the mean is compared on the scale of Sq
            worst = max(worst, r)
            if r > tol:
                failures.append(f"{rel_path} ({g['title']}): {name} frictal {a!r} Gwyddion {b!r} (rel {r:.3g})")
        rows.append((rel_path, g, st, info, worst))
        print(f"{rel_path:45s} {info['reader']:24s} {g['nx']}x{g['ny']} Sq {st['Sq_m']:.10g} vs {g['Sq']:.10g} "
              f"worst rel {worst:.2g}")
    crows = []
    for rel_path, chan in CURVES:
        path = os.path.join(data, rel_path)
        g = gwy.curve_data(path)
        if g is None:
            failures.append(f"{rel_path}: Gwyddion does not load it")
            continue
        info = frictal_json(exe, ["info", path])
        st = frictal_json(exe, ["stats", path, "--detrend", "none"])
        pts = [(x, y) for x, y in zip(g["x"], g["y"]) if math.isfinite(y)]
        # frictal's profile statistics are those of the piecewise-linear profile (docs/analysis.md):
        # mean = integral of z / L, rms about it = sqrt(integral of (z - mean)^2 / L), each segment
        # integrated exactly (trapezoid; (a^2 + a b + b^2) / 3 for the square).
        length = pts[-1][0] - pts[0][0]
        mean = sum((x1 - x0) * (y0 + y1) / 2 for (x0, y0), (x1, y1) in zip(pts, pts[1:])) / length
        rq = math.sqrt(sum((x1 - x0) * ((y0 - mean) ** 2 + (y0 - mean) * (y1 - mean) + (y1 - mean) ** 2) / 3
                           for (x0, y0), (x1, y1) in zip(pts, pts[1:])) / length)
        for name, a, b in [("length", st["length_m"], length), ("rms height", st["rms_height_m"], rq)]:
            if rel(a, b) > RTOL:
                failures.append(f"{rel_path}: {name} frictal {a!r} Gwyddion's curve {b!r}")
        if abs(st["mean_height_m"] - mean) > RTOL * rq:
            failures.append(f"{rel_path}: mean frictal {st['mean_height_m']!r} Gwyddion's curve {mean!r}")
        if st["points"] != len(pts):
            failures.append(f"{rel_path}: {st['points']} points, Gwyddion's curve has {len(pts)}")
        y = pts
        crows.append((rel_path, g, st, info, len(y), length, rq, mean))
        print(f"{rel_path:45s} {info['reader']:24s} {len(y)} points, length {st['length_m']:.10g} vs {length:.10g}, "
              f"rms height {st['rms_height_m']:.10g} vs {rq:.10g}")
    if out_md:
        with open(out_md, "w") as f:
            f.write("| file | frictal reader | Gwyddion module, channel | grid | n dx x n dy (m) | valid | "
                    "Sq frictal (m) | Sq Gwyddion (m) | largest rel. difference (mean, Sq, Sa, Ssk, Sku, Sz, sizes) | "
                    "Sdq rel. difference |\n")
            f.write("|---|---|---|---|---|---|---|---|---|---|\n")
            for rel_path, g, st, info, worst in rows:
                f.write(f"| {os.path.basename(rel_path)} | {info['reader']} | {g['module']} {g['id']} "
                        f"'{g['title']}' | {g['nx']} x {g['ny']} | {g['sx']:.6g} x {g['sy']:.6g} | {g['valid']} | "
                        f"{st['Sq_m']:.10g} | {g['Sq']:.10g} | {worst:.1e} | {g['Sdq_rel']:.1e}"
                        f"{'' if g['Sdq_compared'] else ' (definitions differ)'} |\n")
            for rel_path, g, st, info, n, length, rq, mean in crows:
                worst = max(rel(st["length_m"], length), rel(st["rms_height_m"], rq), abs(st["mean_height_m"] - mean) / rq)
                f.write(f"| {os.path.basename(rel_path)} | {info['reader']} | {g['module']} curve 0 | {n} points | "
                        f"length {length:.6g} | {n} | Rq {st['rms_height_m']:.10g} | Rq {rq:.10g} | {worst:.1e} "
                        f"(length, mean, Rq) | |\n")
    for m in failures:
        print("FAIL:", m)
    print(f"{len(rows)} image channels and {len(crows)} curves compared, {len(failures)} disagreements")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
