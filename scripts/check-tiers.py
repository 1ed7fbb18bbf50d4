#!/usr/bin/env python3
"""Checks that every include in src/ goes only downward in the module tiers of src/tiers.txt.

A source or header in src/<module>/ may include
  - its own headers ("name.hpp" or "<module>/name.hpp"),
  - a public header (include/frictal/) of base, of its own module or of a module below it,
  - a shared header (tiers.txt, third column) of a module below it ("<below>/name.hpp"),
and a public header may include only public headers of base, its own module or modules below it.
"Below" is the closure of the "uses" column. Each violation is printed as
`file:line: error: <rule>` and the exit status is 1; with --stamp the file is written on success
(the build's custom command). --extra FILE=MODULE checks FILE as if it were in src/MODULE/ (the
test plants a wrong-way include this way).
"""
import argparse
import pathlib
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')


def read_table(path):
    modules = {}  # name -> (uses, headers, shared)
    for n, raw in enumerate(path.read_text().splitlines(), 1):
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        m = re.fullmatch(r"([a-z_]+)\s*:([^|]*)\|([^|]*)\|(.*)", line)
        if not m:
            sys.exit(f"{path}:{n}: error: not 'module : uses | public headers | shared headers'")
        name = m.group(1)
        if name in modules:
            sys.exit(f"{path}:{n}: error: module {name} listed twice")
        uses, headers, shared = (m.group(i).split() for i in (2, 3, 4))
        for u in uses:
            if u not in modules:
                sys.exit(f"{path}:{n}: error: {name} uses {u}, which is not listed above it (the table is in tier order)")
        modules[name] = (uses, headers, shared)
    return modules


def closure(modules):
    below = {}
    for name, (uses, _, _) in modules.items():  # tier order: every use is already closed
        s = set(uses) | {"base"}
        for u in uses:
            s |= below[u]
        below[name] = s - {name}
    return below


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("root", type=pathlib.Path, help="the source tree (holds src/tiers.txt, src/, include/frictal/)")
    ap.add_argument("--table", type=pathlib.Path, help="the tier table (default ROOT/src/tiers.txt)")
    ap.add_argument("--extra", action="append", default=[], metavar="FILE=MODULE",
                    help="also check FILE as a source of src/MODULE/")
    ap.add_argument("--stamp", type=pathlib.Path, help="file written when the check passes")
    a = ap.parse_args()
    root = a.root.resolve()
    table = a.table or root / "src" / "tiers.txt"
    modules = read_table(table)
    below = closure(modules)
    errors = []

    owner = {}
    for name, (_, headers, _) in modules.items():
        for h in headers:
            if h in owner:
                errors.append(f"{table}: error: frictal/{h} is listed under {owner[h]} and {name}")
            owner[h] = name
    public = root / "include" / "frictal"
    for h in sorted(public.glob("*.hpp")):
        if h.name not in owner:
            errors.append(f"{h}: error: public header frictal/{h.name} belongs to no module of {table}")
    src = root / "src"
    for d in sorted(p for p in src.iterdir() if p.is_dir()):
        if d.name not in modules and d.name != "version":
            errors.append(f"{d}: error: src/{d.name}/ is no module of {table}")

    def rule(mod, sub):
        allowed = ", ".join(sorted(below[mod])) or "nothing"
        return f"module {mod} includes {sub}, but {mod} may use only: {allowed} (src/tiers.txt)"

    def check(path, mod, shown):
        for n, text in enumerate(path.read_text(errors="replace").splitlines(), 1):
            m = INCLUDE.match(text)
            if not m:
                continue
            inc = m.group(1)
            head, _, tail = inc.rpartition("/")
            where = f"{shown}:{n}: error:"
            if head == "frictal":
                o = owner.get(tail)
                if o is None:
                    errors.append(f"{where} frictal/{tail} belongs to no module of src/tiers.txt")
                elif o != mod and o != "base" and o not in below[mod]:
                    errors.append(f"{where} {rule(mod, f'frictal/{tail} (public header of {o})')}")
            elif head == "" or head == mod:
                if not (path.parent / tail).exists() and not (src / mod / tail).exists():
                    errors.append(f'{where} "{inc}" is no header of module {mod}')
            elif head in modules:
                if head not in below[mod]:
                    errors.append(f"{where} {rule(mod, f'{inc} (module {head})')}")
                elif "*" not in modules[head][2] and tail not in modules[head][2]:
                    errors.append(f"{where} module {mod} includes {inc}, a private header of {head} "
                                  f"(only its shared headers may be included: "
                                  f"{' '.join(modules[head][2]) or 'none'}; src/tiers.txt)")
            else:
                errors.append(f'{where} "{inc}" is no frictal/ header nor a header of a module')

    for mod in modules:
        if mod == "base":
            continue
        for f in sorted((src / mod).glob("*")):
            if f.suffix in (".cpp", ".hpp", ".h", ".cc", ".in"):
                check(f, mod, f.relative_to(root))
    for h in sorted(public.glob("*.hpp")):
        if h.name in owner:
            check(h, owner[h.name], h.relative_to(root))
    for e in a.extra:
        f, _, mod = e.rpartition("=")
        if mod not in modules:
            sys.exit(f"--extra {e}: no module {mod}")
        check(pathlib.Path(f), mod, f)

    if errors:
        print("\n".join(errors), file=sys.stderr)
        print(f"check-tiers: {len(errors)} include(s) against the module tiers", file=sys.stderr)
        return 1
    if a.stamp:
        a.stamp.write_text("ok\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
