"""The GLSL tree says what it holds: shaders/README.md lists every program, include and
define (a new one must be documented to pass), no include grows past ~250 lines, and the
CSG constants in GLSL are the Python enums' (injected, so they cannot drift)."""

from __future__ import annotations

import re

from glshade.render.shaders import assemble, shader_dir
from glshade.solids.encoding import LeafKind, Op, glsl_defines

from tests.conftest import ROOT

SHADERS = ROOT / "shaders"
README = (SHADERS / "README.md").read_text(encoding="utf-8")


def _sources():
    return [p for p in SHADERS.rglob("*") if p.is_file() and p.name != "README.md"]


def test_every_program_and_include_is_listed():
    include = SHADERS / "include"
    names = [p.relative_to(include).as_posix() if p.is_relative_to(include) else p.name
             for p in _sources()]
    assert len(names) > 30
    assert [n for n in names if f"`{n}`" not in README] == []


def test_every_define_a_program_tests_is_listed():
    tested, defined_inside = set(), set()
    for path in _sources():
        text = path.read_text(encoding="utf-8")
        for line in re.findall(r"^\s*#\s*(?:if|ifdef|ifndef|elif)\b(.*)$", text, re.M):
            tested.update(re.findall(r"\b[A-Z][A-Z0-9_]{2,}\b", line))
        defined_inside.update(re.findall(r"^\s*#\s*define\s+([A-Z][A-Z0-9_]+)", text, re.M))
    guards = {name for name in tested if name.endswith("_GLSL")}
    undocumented = sorted(n for n in tested - guards - defined_inside if f"`{n}" not in README
                          and not any(n.startswith(p) and f"`{p}" in README
                                      for p in ("LEAF_", "CSG_KIND_")))
    assert undocumented == []


def test_no_include_is_a_book():
    long = {p.name: n for p in (SHADERS / "include").rglob("*.glsl")
            if (n := len(p.read_text(encoding="utf-8").splitlines())) > 250}
    assert long == {}


def test_csg_constants_come_from_the_enums():
    defines = dict(d.split(" ", 1) for d in glsl_defines())
    assert {int(defines[f"LEAF_{k.name}"]) for k in LeafKind} == {int(k) for k in LeafKind}
    assert {int(defines[f"OP_{o.name}"].strip("()")) for o in Op} == {int(o) for o in Op}
    # no bare kind or opcode number is left where the GLSL compares a kind or a code
    text = "\n".join(p.read_text(encoding="utf-8")
                     for p in (SHADERS / "include" / "csg").glob("*.glsl"))
    assert not re.findall(r"IS\(kind, \d\)|KIND_LOOP\(\d\)|\b(?:KIND|kind|n) [!=]= \d|"
                          r"code == -\d", text)
    # and a program assembled without them carries the #error that stops its compile
    source, _ = assemble("csg.frag", shader_dir(), ("CSG_WORDS 1",))
    assert "#error" in source
