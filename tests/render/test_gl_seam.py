"""The GL seam, checked: only modules under ``glshade/render/`` make GL objects, so that
every chapter's numpy can be read, tested and imported without a context, and every GL
object has one owner that releases it."""

from __future__ import annotations

import ast
from pathlib import Path

import glshade

PACKAGE = Path(glshade.__file__).parent
#: moderngl's factories of GL objects (Context methods and module functions)
FACTORIES = {"buffer", "texture", "texture_array", "texture_cube", "texture3d",
             "depth_texture", "program", "compute_shader", "framebuffer",
             "simple_framebuffer", "renderbuffer", "depth_renderbuffer", "vertex_array",
             "simple_vertex_array", "sampler", "query", "scope", "external_texture",
             "create_context", "create_standalone_context"}
#: glshade's own factories of GL objects, named by what they are called on
OWN = {("shaders", "compile"), ("ShaderLibrary", None), ("data_texture", None)}


def gl_calls(tree: ast.AST) -> list[tuple[int, str]]:
    """(line, call) of every call in ``tree`` that makes a GL object."""
    found = []
    for node in ast.walk(tree):
        if not isinstance(node, ast.Call):
            continue
        f = node.func
        if isinstance(f, ast.Attribute):
            owner = f.value.attr if isinstance(f.value, ast.Attribute) else getattr(
                f.value, "id", "")
            if f.attr in FACTORIES or (owner, f.attr) in OWN:
                found.append((node.lineno, f"{owner}.{f.attr}"))
        elif isinstance(f, ast.Name) and (f.id, None) in OWN:
            found.append((node.lineno, f.id))
    return found


def test_the_check_finds_what_it_looks_for():
    source = ("ctx.texture((1, 1), 4)\nself.context.ctx.buffer(b'')\n"
              "self.shaders.compile('a', 'b')\nShaderLibrary(c)\nnp.sum(x)\n")
    assert [line for line, _ in gl_calls(ast.parse(source))] == [1, 2, 3, 4]


def test_only_render_makes_gl_objects():
    offenders = []
    for path in sorted(PACKAGE.rglob("*.py")):
        rel = path.relative_to(PACKAGE)
        if rel.parts[0] == "render":
            continue
        for line, call in gl_calls(ast.parse(path.read_text(encoding="utf-8"))):
            offenders.append(f"{rel}:{line}: {call}")
    assert offenders == [], "GL objects made outside glshade/render/:\n" + "\n".join(offenders)
