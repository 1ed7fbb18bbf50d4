#!/usr/bin/python3
"""Writes the documentation site's reference pages from the built frictal, so that no option,
unit, default, range, format or header is copied by hand (scripts/docs/build.py runs it):

    reference/cli.md       `frictal commands --json`: every command, subcommand and option, the
                           options from a settings table with the table's unit, default and range
    reference/settings.md  `frictal settings --markdown` (the settings tables)
    reference/outputs.md   `frictal columns --markdown`, `frictal warnings --markdown` (outputs, warning codes)
    reference/formats.md   `frictal formats --json`, and `frictal info --json` of every measured
                           file under tests/data/ (the instrument files the tests read)
    reference/kinds.md     `frictal study kinds --json`: the study task kinds and their outputs
    reference/cpp.rst      one Breathe section per public header of include/frictal/

    scripts/docs/gen_reference.py --cli path/to/frictal --out STAGED_SOURCE_DIR
"""
import argparse
import glob
import json
import os
import re
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
GENERATED = "<!-- Generated at build time by scripts/docs/gen_reference.py from {what}; do not edit. -->\n\n"


def run(cli, *args):
    r = subprocess.run([cli, *args], capture_output=True, text=True)
    if r.returncode != 0:
        raise SystemExit(f"gen_reference: `frictal {' '.join(args)}` failed: {r.stderr.strip()}")
    return r.stdout


def cell(text):
    """Markdown table cell: no pipes or newlines, code stays code."""
    return str(text).replace("|", "\\|").replace("\n", " ").strip() or "–"


def option_row(o):
    names = ", ".join(f"`{n}`" for n in o["names"])
    if o["positional"]:
        value = f"`{o['value'] or 'VALUE'}`"
    elif o["flag"]:
        value = "flag"
    else:
        value = f"`{o['value']}`" if o["value"] else "value"
    f = o["field"]
    if f:
        return [names, value, f["unit"] or "–", f["default"], f["range"], f["help"] + f" (setting `{f['name']}`)"]
    default = o["default"] if o["default"] else ("required" if o["required"] else "–")
    return [names, value, "–", default, "–", o["description"]]


def command_section(c, level, out):
    out.append(f"{'#' * level} `{c['path']}`\n")
    out.append(f"{c['description']}\n" if c["description"] else "")
    if c["needs_subcommand"]:
        subs = ", ".join(f"`{s['name']}`" for s in c["subcommands"])
        out.append(f"Takes one of: {subs}.\n")
    if c["fallthrough"]:
        out.append("The options of the parent command are also accepted after this subcommand's name.\n")
    if c["options"]:
        out.append("| option | value | unit | default | valid | meaning |\n|---|---|---|---|---|---|")
        for o in c["options"]:
            out.append("| " + " | ".join(cell(x) for x in option_row(o)) + " |")
        out.append("")
    else:
        out.append("No options of its own.\n")
    out.append("```text\n" + c["help"].rstrip() + "\n```\n")
    for s in c["subcommands"]:
        command_section(s, min(level + 1, 6), out)


def cli_page(cli):
    j = json.loads(run(cli, "commands", "--json"))
    out = [GENERATED.format(what="`frictal commands --json`"), "# Command-line reference\n"]
    out.append(j["description"].replace("\n", " ") + "\n")
    out.append(
        "Every command, subcommand and option of `frictal`, as the CLI itself lists them. An option that "
        "comes from one of the library's settings tables shows the table's unit, default and valid range "
        "and the setting's name, which is also its study TOML key, Python keyword and JSON key "
        "([settings reference](settings.md)). Angles are degrees and lengths metres at this interface. "
        "Each command's `--help` text follows its table.\n")
    out.append("| command | what it does |\n|---|---|")
    for c in j["commands"]:
        anchor = c["path"].replace(" ", "-")
        out.append(f"| [`{c['name']}`](#{anchor}) | {cell(c['description'])} |")
    out.append("")
    for c in j["commands"]:
        command_section(c, 2, out)
    return "\n".join(out)


def formats_page(cli):
    j = json.loads(run(cli, "formats", "--json"))
    out = [GENERATED.format(what="`frictal formats --json` and `frictal info --json` of tests/data/"),
           "# File formats\n",
           "What this build of frictal reads, as `frictal formats` lists it: native readers detect the "
           "format by content; the others go through Gwyddion's file modules when Gwyddion is installed "
           f"(here: {'installed' if j['gwyddion'] else 'not installed: ' + j.get('gwyddion_missing', '')}). "
           "The [input guide](../guide/io.md) explains units, channels, invalid points and the writers.\n",
           "## Readers\n", "| format | description | reader | written by `frictal convert` |", "|---|---|---|---|"]
    for f in j["formats"]:
        out.append(f"| `{cell(f['name'])}` | {cell(f['description'])} | {cell(f['reader'])} | "
                   f"{'yes' if f['can_write'] else '–'} |")
    out += ["", "## Measured files the tests read\n",
            "Every file under `tests/data/` (instrument files from other projects' test corpora, with their "
            "provenance in `tests/data/README.md`), as `frictal info` describes it with this build. A file "
            "read through Gwyddion shows the module that read it.\n",
            "| file | reader | kind | points | size | units (xy, z) |", "|---|---|---|---|---|---|"]
    files = []
    for sub in ["instruments", "profiles", "maps", "x3p"]:
        files += sorted(p for p in glob.glob(os.path.join(ROOT, "tests", "data", sub, "*")) if os.path.isfile(p)
                        and not p.endswith(".md"))
    for p in files:
        rel = os.path.relpath(p, os.path.join(ROOT, "tests", "data"))
        r = subprocess.run([cli, "info", p, "--json"], capture_output=True, text=True)
        if r.returncode != 0:
            msg = (r.stderr.strip().splitlines() or ["?"])[0].replace(p, rel)
            out.append(f"| `{rel}` | `frictal info` without options says: {cell(msg)} | – | – | – | – |")
            continue
        i = json.loads(r.stdout)
        ch = i["channels"][i.get("channel", 0)] if i.get("channels") else {}
        if i.get("kind") == "map":
            pts = f"{i['nx']} x {i['ny']}"
            size = f"{ch.get('size_x', 0):.4g} x {ch.get('size_y', 0):.4g} m" if ch else "–"
        else:
            pts = str(i.get("points", i.get("nx", "–")))
            size = f"{i['length_m']:.4g} m" if "length_m" in i else "–"
        units = f"{ch.get('xy_unit', '–')}, {ch.get('z_unit', '–')}" if ch else "–"
        out.append(f"| `{rel}` | {cell(i.get('reader', '–'))} | {cell(i.get('kind', '–'))} | {pts} | {size} | "
                   f"{cell(units)} |")
    return "\n".join(out) + "\n"


def kinds_page(cli):
    j = json.loads(run(cli, "study", "kinds", "--json"))
    out = [GENERATED.format(what="`frictal study kinds --json`"), "# Study task kinds\n",
           "The task kinds a study file's `kind = \"...\"` names, as the registry of this build lists them, "
           "with the outputs each task stores (scalars are columns of `frictal study export`; arrays are "
           "stored per task). The [studies guide](../guide/studies.md) describes the TOML schema, the store "
           "and MPI.\n"]
    for k in j["kinds"]:
        out.append(f"## `{k['name']}`\n\n{k['description']}"
                   f"{'' if k.get('available', True) else ' (not available in this build)'}\n")
        out.append("| output | unit | array | meaning |\n|---|---|---|---|")
        for o in k["outputs"]:
            # an output taken from an output table names its column (the outputs reference)
            src = f" (column `{o['column']}` of table `{o['table']}`)" if o.get("table") else ""
            out.append(f"| `{o['name']}` | {cell(o['unit'])} | {'yes' if o['array'] else '–'} | "
                       f"{cell(o['description'] + src)} |")
        if k.get("plots"):
            out.append("\nPlot views: " + ", ".join(f"`{p['id']}`" for p in k["plots"]) + ".")
        out.append("")
    return "\n".join(out)


def rst_text(text):
    """Plain text for reStructuredText: the characters that would start markup escaped."""
    return re.sub(r"([\\*|_`])", r"\\\1", text)


def cpp_page():
    out = [".. Generated at build time by scripts/docs/gen_reference.py from include/frictal/*.hpp.\n",
           "C++ API\n=======\n",
           "The public API is ``include/frictal/``: one header per module, each documented in its doc "
           "comments, from which this page is generated (Doxygen XML, Breathe). Link with "
           "``find_package(frictal CONFIG REQUIRED)`` and ``target_link_libraries(app PRIVATE frictal::frictal)``. "
           "Units are SI (metres, radians, seconds, kilograms); every field says its unit.\n",
           "Headers\n-------\n",
           "What each header owns, from its opening comment:\n"]
    for h in sorted(glob.glob(os.path.join(ROOT, "include", "frictal", "*.hpp"))):
        lines = []  # the header's opening comment up to its first blank line: what the module owns
        with open(h) as f:
            for line in f:
                if not line.startswith("//") or not line.strip("/ \n"):
                    break
                lines.append(line.lstrip("/").strip())
        text = " ".join(lines)
        if len(text) > 420:  # the long ones (dem.hpp) go on about the design: their first sentences
            text = text[:text.rfind(". ", 0, 420) + 1] + " (more in the header)"
        out.append(f"``frictal/{os.path.basename(h)}``\n   {rst_text(text) or '(no description)'}\n")
    # One section per namespace (a namespace spans several headers, so per-file sections would
    # declare it once per header); detail namespaces are excluded in the Doxyfile.
    namespaces = set()
    for h in glob.glob(os.path.join(ROOT, "include", "frictal", "*.hpp")):
        namespaces.update(re.findall(r"^namespace (frictal(?:::\w+)*) \{", open(h).read(), re.M))
    for ns in sorted(namespaces, key=lambda n: (n != "frictal", n)):
        title = f"Namespace {ns}"
        out.append(f"{title}\n{'-' * len(title)}\n")
        out.append(f".. doxygennamespace:: {ns}\n   :project: frictal\n   :content-only:\n   :members:\n   "
                   ":protected-members:\n   :undoc-members:\n")
    return "\n".join(out)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cli", required=True)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    ref = os.path.join(a.out, "reference")
    os.makedirs(ref, exist_ok=True)
    pages = {
        "cli.md": cli_page(a.cli),
        "settings.md": GENERATED.format(what="`frictal settings --markdown`") + run(a.cli, "settings", "--markdown"),
        "formats.md": formats_page(a.cli),
        "kinds.md": kinds_page(a.cli),
        "outputs.md": GENERATED.format(what="`frictal columns --markdown` and `frictal warnings --markdown`")
        + "# Outputs reference\n\n"
        + "Every key that a command's `--json` and Python's dicts print, table by table, declared once in "
        + "the library's output tables (`frictal/outputs.hpp`; each result type's table beside it, e.g. "
        + "`prediction_columns()`, `signature_columns()`, `tilt_columns()`), with its interface unit. The "
        + "CLI's JSON is in the interface unit (degrees for `deg`); Python's dicts hold SI values (radians) "
        + "under the Python key; `Prediction.to_dict()` has the JSON's keys and units, and the report embeds "
        + "the same object as `<script type=\"application/json\" id=\"prediction\">`. A unit `object:T` is a "
        + "nested object with the columns of table T, `list:T` a list of them, `settings` an object of "
        + "settings (the [settings reference](settings.md)). A test (tests/outputs/check_output_keys.py) "
        + "runs every command and Python function and checks each key it prints against these tables.\n\n"
        + run(a.cli, "columns", "--markdown")
        + "\n## Warning codes\n\n"
        + "A number computed without error that a reader should not trust as it stands carries one of "
        + "these codes (`frictal/warnings.hpp`): in the JSON's `warnings`, on standard error, in the "
        + "report beside the headline, and in Python as `warnings.warn` with the category "
        + "`frictal.<CamelCase code>Warning` (a subclass of `frictal.FrictalWarning`).\n\n"
        + run(a.cli, "warnings", "--markdown"),
        "cpp.rst": cpp_page(),
    }
    for name, text in pages.items():
        with open(os.path.join(ref, name), "w") as f:
            f.write(text)


if __name__ == "__main__":
    main()
