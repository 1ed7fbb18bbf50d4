# Sphinx configuration of frictal's documentation site. Not run from here: scripts/docs/build.py
# stages this folder with the generated pages (CLI, formats, settings, C++ XML) into
# BUILD/docs/src and runs sphinx-build there with warnings as errors, offline.
import os

import frictal

project = "frictal"
author = "the frictal developers"
copyright = "the frictal developers"
version = release = frictal.__version__

extensions = [
    "myst_parser",  # the Markdown guides of docs/ as pages
    "nbsphinx",  # tutorials: notebooks executed at every build
    "breathe",  # C++ API from Doxygen's XML of include/frictal/
    "sphinx.ext.autodoc",  # Python API from the built module's docstrings
    "sphinx.ext.mathjax",
    "matplotlib.sphinxext.plot_directive",  # theory figures computed by frictal at build time
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
exclude_patterns = ["_build", "**.ipynb_checkpoints"]
root_doc = "index"
# Option names stay as typed: no "--" turned into an en dash, no curly quotes in CLI text.
smartquotes = False

html_theme = "sphinx_rtd_theme"
html_title = f"frictal {release}"
html_static_path = ["_static"]
html_css_files = ["frictal.css"]
html_theme_options = {"navigation_depth": 3, "collapse_navigation": False}
html_show_sourcelink = False

# Offline: MathJax from Debian's libjs-mathjax, copied into _static by the build script; no CDN.
# Debian 12 packages MathJax 2.7: its tex2jax must process the math spans that MyST and nbsphinx
# mark with the class "math" inside sections they mark to be ignored (classes meant for MathJax 3).
mathjax_path = "mathjax/MathJax.js?config=TeX-AMS_CHTML"
mathjax2_config = {
    "tex2jax": {
        "inlineMath": [["\\(", "\\)"]],
        "displayMath": [["\\[", "\\]"]],
        "processEscapes": True,
        "ignoreClass": "tex2jax_ignore|mathjax_ignore|document",
        "processClass": "tex2jax_process|mathjax_process|math|output_area",
    }
}

# MyST: $...$ math in Markdown, heading anchors so that links to "#a-section" work.
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence", "deflist"]
myst_heading_anchors = 3
# The guides of docs/ start with one "# Title" and are included unchanged; a few of them skip a
# heading level (### under #), which MyST reports as myst.header: that is their style, not an error.
suppress_warnings = ["myst.header"]

# Notebooks: executed at every build; a cell that raises fails the build.
nbsphinx_execute = "always"
nbsphinx_allow_errors = False
nbsphinx_timeout = 300
nbsphinx_kernel_name = "python3"
nbsphinx_requirejs_path = ""  # no widgets, so no require.js from a CDN
nbsphinx_prolog = """
.. note::

   This page is a Jupyter notebook executed when the site was built, with the frictal it
   documents: every number and figure below was computed then. Download it
   (:download:`{{ env.doc2path(env.docname, base=None).split('/')[-1] }}
   <{{ env.doc2path(env.docname, base=None).split('/')[-1] }}>`) to run it cell by cell.
"""

# Matplotlib's plot directive: figures made at build time, PNG only, no source links.
plot_formats = [("png", 110)]
plot_html_show_source_link = False
plot_html_show_formats = False
plot_include_source = False
plot_rcparams = {"figure.figsize": (7.0, 3.6), "figure.autolayout": True, "savefig.bbox": "tight"}

# C++: Doxygen XML written by the build script.
breathe_projects = {"frictal": os.environ.get("FRICTAL_DOXYGEN_XML", "../doxygen/xml")}
breathe_default_project = "frictal"
breathe_default_members = ("members",)
breathe_show_include = True

# Python: the built module (PYTHONPATH set by the build script).
autodoc_default_options = {"members": True, "undoc-members": True, "show-inheritance": True}
autodoc_member_order = "bysource"


def _plain_docstring(app, what, name, obj, options, lines):
    """The extension's docstrings are plain text (pybind11), not reStructuredText: escape the
    characters that would start markup (``**params``, ``|x|``), except in doctest lines, and make
    the indented keyword lines of the generators and tilt() a bullet list, one keyword per item."""
    if not name.startswith("frictal") or name == "frictal" or name.startswith("frictal.plots"):
        return
    out, in_list = [], False
    for line in lines:
        if line.lstrip().startswith(">>>"):
            out.append(line)
            continue
        text = line.strip().replace("\\", "\\\\").replace("*", "\\*").replace("|", "\\|").replace("`", "\\`")
        item = line.startswith((" ", "\t")) and text != ""
        if item and not in_list:
            out.append("")
        if not item and in_list and text:
            out.append("")
        out.append(f"- {text}" if item else text)
        in_list = item
    lines[:] = out


def setup(app):
    app.connect("autodoc-process-docstring", _plain_docstring)
