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
