"""CSG trees written as text, for scene files (``[[solid]] tree = "..."``) and the command
line (``solid:TEXT``): leaves ``sphere(r)``, ``box(s)`` or ``box(x, y, z)``,
``cylinder(r, h)``, ``cone(r, h)``, ``torus(R, r)``, ``halfspace([nx, ny, nz], d)``;
operators ``|`` (union), ``&`` (intersection), ``-`` (difference), parentheses; and
methods ``.move(x, y, z)``, ``.scale(s)`` or ``.scale(x, y, z)``, ``.turn(degrees, [ax,
ay, az])`` and ``.transform([[...4 rows...]])``. Example::

    (box(2, 1, 2) - cylinder(0.4, 3).turn(90, [1, 0, 0])) | sphere(0.6).move(0, 0.8, 0)

Parsed by Python's own parser (``ast``) and evaluated by walking the tree: only numbers,
lists and these names are allowed, so a scene file cannot run code."""

from __future__ import annotations

import ast

import numpy as np

from ..errors import GlshadeError, InputError

__all__ = ["parse_solid"]


def _leaves():
    from . import leaves as S

    def box(*s):
        if len(s) not in (1, 3):
            raise InputError(f"box takes a size or three sizes (x, y, z), got {len(s)}")
        return S.Box(s[0] if len(s) == 1 else list(s))

    return {"sphere": S.Sphere, "box": box,
            "cylinder": S.Cylinder, "cone": S.Cone, "torus": S.Torus,
            "halfspace": S.HalfSpace}


def _turn(solid, degrees, axis):
    a = np.asarray(axis, np.float64)
    if a.shape != (3,) or not np.linalg.norm(a):
        raise InputError(f"turn needs an axis of 3 numbers, not all zero; got {axis!r}")
    half = np.radians(float(degrees)) / 2
    return solid.rotated([*(np.sin(half) * a / np.linalg.norm(a)), np.cos(half)])


def _scale(solid, *f):
    return solid.scaled(f[0] if len(f) == 1 else list(f))


_METHODS = {"move": lambda s, *v: s.translated(v[0] if len(v) == 1 else list(v)),
            "scale": _scale, "turn": _turn,
            "transform": lambda s, m: s.transformed(m)}
_OPS = {ast.BitOr: "__or__", ast.BitAnd: "__and__", ast.Sub: "__sub__"}


def parse_solid(text: str, where: str = "solid"):
    """The Solid a text describes; a mistake is an InputError naming ``where`` and the
    offending piece.

    Parameters
    ----------
    text : str
        The solid's text (``box(2) - cylinder(0.5, 3)``).
    where : str
        Where it came from, for errors.
    """
    try:
        # (in parentheses: a tree may run over several lines)
        tree = ast.parse(f"(\n{text.strip()}\n)", mode="eval")
    except (RecursionError, MemoryError):
        raise InputError(f"{where}: the expression is nested too deeply to read (parentheses "
                         "inside parentheses); write long runs flat: a | b | c ...") from None
    except SyntaxError as exc:
        lines = text.strip().splitlines()
        line = (exc.lineno or 0) - 1  # (line 0 and the last are the wrapping parentheses)
        if line > len(lines):
            at = "; it ends too early"
        elif line < 1:
            at = ""  # (a parenthesis left open: the message says so)
        else:
            at = "; " + (f"line {line}, " if len(lines) > 1 else "") + f"column {exc.offset}"
        raise InputError(f"{where}: not a CSG expression ({exc.msg}{at}): "
                         f"{text.strip()!r}") from None
    leaves = _leaves()

    def value(node):
        if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)) and \
                not isinstance(node.value, bool):
            return float(node.value)
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub):
            return -value(node.operand)
        if isinstance(node, (ast.List, ast.Tuple)):
            return [value(e) for e in node.elts]
        raise InputError(f"{where}: expected a number or a list of numbers, got "
                         f"{ast.unparse(node)!r}")

    def not_a_solid(node):
        return InputError(f"{where}: {ast.unparse(node)!r} is not a solid: use "
                          f"{', '.join(leaves)}(...), |, &, -, and .move/.scale/.turn/"
                          ".transform")

    def solid(root):
        """Evaluated without recursion (a 1,000-long chain of | or .move is fine): a
        post-order walk with an explicit stack of pending nodes and a stack of values."""
        values: list = []
        work: list = [(root, False)]
        while work:
            node, ready = work.pop()
            if isinstance(node, ast.BinOp) and type(node.op) in _OPS:
                if ready:
                    right, left = values.pop(), values.pop()
                    values.append(getattr(left, _OPS[type(node.op)])(right))
                else:
                    work += [(node, True), (node.right, False), (node.left, False)]
                continue
            if isinstance(node, ast.Call) and not node.keywords:
                f = node.func
                if isinstance(f, ast.Name) and f.id in leaves:
                    values.append(leaves[f.id](*[value(a) for a in node.args]))
                    continue
                if isinstance(f, ast.Attribute) and f.attr in _METHODS:
                    if ready:
                        values.append(_METHODS[f.attr](values.pop(),
                                                       *[value(a) for a in node.args]))
                    else:
                        work += [(node, True), (f.value, False)]
                    continue
            raise not_a_solid(node)
        return values[0]

    try:
        return solid(tree.body)
    except (GlshadeError, TypeError, ValueError) as exc:
        if isinstance(exc, InputError) and str(exc).startswith(f"{where}: "):
            raise
        raise InputError(f"{where}: {exc}") from None
