"""Sphinx configuration of the navlib site (``make docs``).

The sources are assembled by ``tools/build_site.py`` into ``build/site-src/`` (the executed notebooks of the
last ``make reproduce``, pages generated from the results files and the README, the API pages) and
built into ``build/site/`` with this configuration (copied beside the sources). Everything the pages
load is served from the site itself: MathJax from the npm package pinned in ``docs/package.json``,
fonts and scripts from the theme; widget JavaScript from a CDN is switched off.
"""

from __future__ import annotations

import re

from docutils import nodes

import navlib

project = "navlib"
author = "The navlib developers"
copyright = "2026, the navlib developers (MIT licence)"  # noqa: A001 -- Sphinx's name
release = version = navlib.__version__

extensions = ["myst_nb", "sphinx.ext.autodoc", "sphinx.ext.napoleon", "sphinx.ext.mathjax"]
exclude_patterns = ["_build", "**.ipynb_checkpoints"]
# ref.python: docstring types such as "n" match several attributes
suppress_warnings = ["mystnb.unknown_mime_type", "myst.header", "ref.python"]

# Notebooks are rendered as executed by `make reproduce`, never executed again.
nb_execution_mode = "off"
nb_ipywidgets_js = {}  # no widget JavaScript from a CDN (explorers draw a static default headless)
nb_merge_streams = True
nb_render_markdown_format = "myst"  # computed captions and answers hold maths ($K_i = 0$) like the text cells
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence", "html_image"]
myst_heading_anchors = 3
# The chapters write display maths as Jupyter does: $$...$$ may open inside a paragraph.
myst_dmath_double_inline = True

# numpydoc-style docstrings through napoleon; members as listed in each module's __all__.
napoleon_numpy_docstring = True
napoleon_google_docstring = False
napoleon_use_ivar = True  # "Attributes" as a field list: autodoc documents the fields themselves
napoleon_custom_sections = [("What the filter does with bad samples", "notes_style")]
autodoc_default_options = {"members": True, "show-inheritance": True}
autodoc_member_order = "bysource"
autodoc_typehints = "description"
autodoc_preserve_defaults = True
# numpy's ArrayLike is a long Union: show the alias names of navlib._typing instead.
autodoc_type_aliases = (
    {
        name: f"navlib._typing.{name}"
        for name in ("ArrayLike", "Array", "Scalar", "Vec3", "Vec3Series", "Quat", "Dcm", "Angles", "Times", "Interval")
    }
    | {
        name: f"navlib._validate.{name}"
        for name in ("Real", "Positive", "NonNegative", "Count", "Flag", "Rng", "Text", "Limit", "Step", "Is")
    }
    | {"EllipsoidArg": "navlib.earth.EllipsoidArg"}
)

# MathJax 3 from the site's own _static (tools/build_site.py copies it from docs/node_modules, pinned in
# docs/package.json and installed by `make docs` with npm ci): offline, no CDN. myst-parser adds the
# classes of its math to mathjax3_config.
mathjax_path = "mathjax/tex-mml-chtml.js"

html_theme = "sphinx_book_theme"
html_title = "navlib"
html_static_path = ["_static"]
html_extra_path = ["_extra"]
html_js_files = ["ledger.js"]
html_css_files = ["navlib.css"]
html_favicon = "_static/favicon.svg"  # the site's own (else the browser asks for /favicon.ico)
html_last_updated_fmt = None
html_domain_indices = False  # the API index (api/index) lists the modules by group
html_copy_source = True  # the download button serves each chapter's .ipynb
html_sourcelink_suffix = ""
html_context = {"default_mode": "light"}  # an explicit mode: the theme logs an error for an unset one
html_theme_options = {
    "repository_url": "https://github.com/navlib-repro/navlib",
    "use_repository_button": True,
    "use_download_button": True,
    "home_page_in_toc": True,
    "show_toc_level": 2,
}


# Docstrings write absolute values as |f| and |w|dt: plain text, not reStructuredText substitutions.
_BARS = re.compile(r"(?<![\\|])\|(\S[^|\n]{0,40}?\S|\S)\|")
_LITERAL = re.compile(r"(:math:`[^`]*`|``[^`]*``)")  # maths and code: bars kept as written


def _escape_bars(app, what, name, obj, options, lines):
    in_math = False
    for i, line in enumerate(lines):
        if line.strip().startswith(".. math::"):
            in_math = True
        elif in_math and line.strip() and not line.startswith((" ", "\t")):
            in_math = False
        if not in_math:
            parts = _LITERAL.split(line)
            lines[i] = "".join(p if k % 2 else _BARS.sub(r"\\|\1\\|", p) for k, p in enumerate(parts))


def _top_level(tex: str) -> str:
    """``tex`` without its ``\\begin{...}...\\end{...}`` environments (where a line break is the environment's own)."""
    depth, out = 0, []
    for part in re.split(r"(\\begin\{[^}]*\}|\\end\{[^}]*\})", tex):
        depth += part.startswith("\\begin{") - part.startswith("\\end{")
        if depth == 0 and not part.startswith("\\end{"):
            out.append(part)
    return "".join(out)


def _tagged_math(app, doctree):
    """Numbered display maths (``\\tag``) as an amsmath environment.

    Sphinx wraps display maths that contains a line break in ``split``, where ``\\tag`` is not allowed (MathJax
    shows an error instead of the equation), even when the break belongs to a matrix. A tagged equation is
    written out as ``equation`` (one line; its matrices keep their rows) or ``gather`` (several lines).
    """
    for node in doctree.findall(nodes.math_block):
        tex = node.astext()
        if node.get("nowrap") or "\\tag" not in tex:
            continue
        env = "gather" if "\\\\" in _top_level(tex) else "equation"
        node[:] = [nodes.Text(f"\\begin{{{env}}}{tex}\\end{{{env}}}")]
        node["nowrap"] = True


def setup(app):
    app.connect("autodoc-process-docstring", _escape_bars)
    app.connect("doctree-read", _tagged_math)
