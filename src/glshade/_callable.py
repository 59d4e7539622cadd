"""Packages that share their name with a public function: ``glshade.compare`` and
``glshade.animate`` are the README's functions, and also packages. Once a package is
imported, Python binds the package to that name in ``glshade``; making the package
callable keeps ``glshade.compare(...)`` working either way."""

from __future__ import annotations

import sys
import types

__all__ = ["callable_package"]


def callable_package(module_name: str, function) -> None:
    """Make the module ``module_name`` call ``function`` when called."""

    class _Callable(types.ModuleType):
        __doc__ = sys.modules[module_name].__doc__

        def __call__(self, *args, **kwargs):
            return function(*args, **kwargs)

    sys.modules[module_name].__class__ = _Callable
