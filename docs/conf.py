"""Sphinx configuration of the shaftfem docs: Markdown pages (MyST), the furo theme, and
the API pages from the docstrings (autodoc). Build: make docs (strict: warnings fail)."""

project = "shaftfem"
author = "the shaftfem developers"
copyright = "2026, the shaftfem developers"

extensions = ["myst_parser", "sphinx.ext.autodoc"]
source_suffix = {".md": "markdown"}
exclude_patterns = ["_build"]
myst_heading_anchors = 3          # links to a page's sections: page.md#a-heading
myst_enable_extensions = ["dollarmath"]

html_theme = "furo"
html_title = "shaftfem"
html_static_path = ["_static"]
html_css_files = ["console.css"]
# a block without a language is program output, not Python
highlight_language = "text"
# "--accuracy" stays two hyphens: the docs name command-line flags
smartquotes = False

autodoc_member_order = "bysource"
autodoc_typehints = "signature"
autodoc_class_signature = "separated"   # a dataclass's long field list stays out of its title
autodoc_default_options = {"exclude-members": "__init__, __new__"}
