"""Sphinx configuration of glshade's documentation: the README as the front page, the
chapter notebooks as tutorials (executed at build time by myst-nb), and the API reference
generated from the docstrings (autodoc + autosummary). Built with warnings as errors."""

import os
import shutil
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
# the API pages are made anew each build (a renamed module must not leave a stale page)
shutil.rmtree(ROOT / "docs" / "api" / "generated", ignore_errors=True)
sys.path.insert(0, str(ROOT / "src"))
os.environ.setdefault("GLSHADE_BACKEND", "auto")

import glshade  # noqa: E402

project = "glshade"
author = "The glshade developers"
copyright = "the glshade developers"
release = version = glshade.__version__

extensions = [
    "myst_nb",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.napoleon",
    "sphinx.ext.viewcode",
    "sphinx.ext.mathjax",
]
exclude_patterns = ["_build", "**.ipynb_checkpoints", "api/generated/*.rst.tmp"]
source_suffix = {".rst": "restructuredtext", ".md": "myst-nb", ".ipynb": "myst-nb"}
myst_enable_extensions = ["colon_fence", "dollarmath"]
myst_heading_anchors = 3

# the notebooks run at build time, top to bottom; an error in any cell fails the build
nb_execution_mode = os.environ.get("GLSHADE_DOCS_EXECUTE", "force")  # ("off": a quick look)
nb_execution_timeout = 600
nb_execution_raise_on_error = True
nb_execution_show_tb = True

autosummary_generate = True
autosummary_imported_members = False  # (each object once: where it is defined)
autodoc_default_options = {"members": True, "show-inheritance": False, "ignore-module-all": True,
                           "member-order": "bysource"}
autodoc_typehints = "description"
autodoc_typehints_format = "short"
napoleon_numpy_docstring = True
napoleon_google_docstring = False
suppress_warnings = ["myst.header"]

html_theme = "pydata_sphinx_theme"
html_title = f"glshade {version}"
html_theme_options = {"navigation_with_keys": False, "show_toc_level": 2}
html_static_path: list[str] = []
