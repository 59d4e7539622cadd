"""Closed-form form factors of the textbook configurations (Siegel and Howell's catalogue),
the independent oracle of the hemicube."""

from math import atan, log, pi, sqrt


def parallel_rectangles(a: float, b: float, c: float) -> float:
    """Between directly opposed a x b rectangles, c apart."""
    x, y = a / c, b / c
    return 2 / (pi * x * y) * (
        log(sqrt((1 + x * x) * (1 + y * y) / (1 + x * x + y * y)))
        + x * sqrt(1 + y * y) * atan(x / sqrt(1 + y * y))
        + y * sqrt(1 + x * x) * atan(y / sqrt(1 + x * x)) - x * atan(x) - y * atan(y))


def perpendicular_rectangles(length: float, height: float, width: float) -> float:
    """From a ``length x width`` rectangle to a ``length x height`` one sharing its edge of
    ``length``, at right angles."""
    h, w = height / length, width / length
    hw = h * h + w * w
    term = ((1 + w * w) * (1 + h * h) / (1 + hw)) * \
        (w * w * (1 + hw) / ((1 + w * w) * hw)) ** (w * w) * \
        (h * h * (1 + hw) / ((1 + h * h) * hw)) ** (h * h)
    return 1 / (pi * w) * (w * atan(1 / w) + h * atan(1 / h) - sqrt(hw) * atan(1 / sqrt(hw))
                           + log(term) / 4)


def coaxial_disks(r1: float, r2: float, d: float) -> float:
    """From a disk of radius r1 to a parallel coaxial one of radius r2, d apart."""
    a, b = r1 / d, r2 / d
    x = 1 + (1 + b * b) / (a * a)
    return (x - sqrt(x * x - 4 * (b / a) ** 2)) / 2


def parallel_offset_rectangles(first, second, z: float) -> float:
    """From the rectangle ``first = (x1, x2, y1, y2)`` to ``second = (xi1, xi2, eta1,
    eta2)`` in a parallel plane ``z`` away, sides along the same axes, anywhere in their
    planes (Howell's catalogue C-11: a signed sum of G over the 16 corner pairings)."""
    def g(x, y, eta, xi):
        u, v = x - xi, y - eta
        a, b = sqrt(u * u + z * z), sqrt(v * v + z * z)
        return (v * a * atan(v / a) + u * b * atan(u / b)
                - z * z / 2 * log(u * u + v * v + z * z)) / (2 * pi)

    (x1, x2, y1, y2), (xi1, xi2, e1, e2) = first, second
    total = sum((-1) ** (i + j + k + m) * g(x, y, e, xi)
                for i, x in enumerate((x1, x2)) for j, y in enumerate((y1, y2))
                for k, e in enumerate((e1, e2)) for m, xi in enumerate((xi1, xi2)))
    return total / ((x2 - x1) * (y2 - y1))


def point_to_rectangle(a: float, b: float, c: float) -> float:
    """From a point to an ``a x b`` rectangle parallel to its plane, ``c`` above the point,
    with one corner straight above it."""
    x, y = a / c, b / c
    return (x / sqrt(1 + x * x) * atan(y / sqrt(1 + x * x))
            + y / sqrt(1 + y * y) * atan(x / sqrt(1 + y * y))) / (2 * pi)
