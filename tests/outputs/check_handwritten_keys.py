"""No new hand-written output key: the front ends write keys from the output tables.

Every output key belongs in an output table (frictal/outputs.hpp) and is written by the generic
writers. This test lists every site in apps/ and python/src/ that writes a key by hand:

  subscript   j["key"] = ...,  d["key"] = ...,  j["key"][k] = ...,  j["key"].push_back(...)
  literal     {{"key", value}, {"key2", value2}}  (a JSON object or dict written as an initializer)

and compares them with the checked-in list of the sites that remain (handwritten_keys.txt, one
line per site: file, then the site; a key written twice in one file is listed twice). The test
fails on a site that is not listed (write the key from its result type's column table instead)
and on a listed site that no longer exists (delete its line: the list only shrinks).

    check_handwritten_keys.py SOURCE_DIR [--print]

--print writes the list of the sites found now (the list's format) and exits 0.
"""
import collections
import os
import re
import sys

ROOTS = ("apps", "python/src")
EXTENSIONS = (".cpp", ".hpp", ".h", ".cc")
LIST = os.path.join(os.path.dirname(os.path.abspath(__file__)), "handwritten_keys.txt")

# j["key"] = / d["key"][x] = / j["key"].push_back( ... (not ==, not a read).
SUBSCRIPT = re.compile(r'\b([A-Za-z_][A-Za-z_0-9]*)\["([A-Za-z_0-9]+)"\]((?:\[[^\]\n]*\])*)\s*(=(?!=)|\.push_back\(|\.emplace_back\()')
# An initializer whose first element is a {"key", ...} pair: a JSON object or dict literal.
LITERAL_START = re.compile(r'\{\s*\{\s*"([a-z_][a-z_0-9]*)"\s*,')
# Declarations whose {{"name", value}} initializers are lookup tables, not outputs.
NOT_OUTPUT = re.compile(r'std::(map|unordered_map|pair|vector<\s*std::pair)')


def strip_comments(text):
    """The text with // and /* */ comments blanked (string literals kept), lines preserved."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if c == '"':
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            out.append(text[i:j + 1])
            i = j + 1
        elif c == "'" and i + 2 < n:
            j = i + 1
            while j < n and text[j] != "'":
                j += 2 if text[j] == "\\" else 1
            out.append(text[i:j + 1])
            i = j + 1
        elif text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append("".join("\n" if ch == "\n" else " " for ch in text[i:j]))
            i = j
        else:
            out.append(c)
            i += 1
    return "".join(out)


def literal_keys(text, start):
    """The keys of the pairs {"key", ...} at the top level of the initializer opening at `start`."""
    keys = []
    depth = 0
    i, n = start, len(text)
    while i < n:
        c = text[i]
        if c == '"':
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            i = j + 1
            continue
        if c == "{":
            depth += 1
            if depth == 2:
                m = re.match(r'\{\s*"([a-z_][a-z_0-9]*)"\s*,', text[i:])
                if m:
                    keys.append(m.group(1))
        elif c == "}":
            depth -= 1
            if depth == 0:
                return keys, i
        i += 1
    return keys, n


def sites_in(text):
    """The hand-written key sites of C++ source `text`."""
    text = strip_comments(text)
    found = []
    for m in SUBSCRIPT.finditer(text):
        found.append(f'{m.group(1)}["{m.group(2)}"]')
    i = 0
    while True:
        m = LITERAL_START.search(text, i)
        if not m:
            break
        line_start = text.rfind("\n", 0, m.start()) + 1
        prev = text[line_start:m.start()]
        keys, end = literal_keys(text, m.start())
        if not NOT_OUTPUT.search(prev):
            found.extend(f'{{"{k}", ...}}' for k in keys)
        i = max(end, m.end())
    return found


def sites_of(path, rel):
    return [f"{rel} {s}" for s in sites_in(open(path, encoding="utf-8").read())]


# The detector on planted code: every form is found, reads, comparisons, comments and lookup
# tables are not (a detector that finds nothing would pass any tree).
PLANTED = r"""
  j["a"] = 1;  d["b"][k] = x;  j["c"].push_back(y);  j["d"]["e"] = z;
  nlohmann::json o = {{"f", 1}, {"g", {1, 2}}};  out.push_back({{"h", a}, {"i", b}});
  if (j["r"] == 2) return j["s"];  // j["t"] = 3;
  /* d["u"] = 4; */ const std::map<std::string, int> m = {{"v", 1}};  auto w = "x[\"y\"] = 1";
"""
PLANTED_SITES = ['j["a"]', 'd["b"]', 'j["c"]', 'j["d"]', '{"f", ...}', '{"g", ...}', '{"h", ...}', '{"i", ...}']


def scan(source):
    sites = []
    for root in ROOTS:
        for dirpath, dirnames, filenames in os.walk(os.path.join(source, root)):
            dirnames.sort()
            for name in sorted(filenames):
                if name.endswith(EXTENSIONS):
                    path = os.path.join(dirpath, name)
                    sites.extend(sites_of(path, os.path.relpath(path, source).replace(os.sep, "/")))
    return sites


def main():
    source = sys.argv[1]
    planted = sites_in(PLANTED)
    if sorted(planted) != sorted(PLANTED_SITES):
        print(f"FAIL: the detector finds {planted} in the planted code, expected {PLANTED_SITES}")
        return 1
    found = scan(source)
    if "--print" in sys.argv[2:]:
        print("\n".join(found))
        return 0
    listed = [ln.strip() for ln in open(LIST, encoding="utf-8") if ln.strip() and not ln.startswith("#")]
    have, allowed = collections.Counter(found), collections.Counter(listed)
    failures = []
    for site, count in sorted(have.items()):
        if count > allowed[site]:
            failures.append(f"new hand-written output key: {site} (x{count - allowed[site]}): declare it in its result "
                            "type's column table and write it with the generic writers (frictal/outputs.hpp)")
    for site, count in sorted(allowed.items()):
        if count > have[site]:
            failures.append(f"{os.path.relpath(LIST, source)}: '{site}' is listed {count} time(s) but found "
                            f"{have[site]} time(s): delete {count - have[site]} such line(s) (the list only shrinks)")
    per_file = collections.Counter(s.split(" ", 1)[0] for s in found)
    print(f"{len(found)} hand-written key sites in {len(per_file)} files (listed: {len(listed)})")
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
