"""``make test``'s backend passes (the 4.1 tier, OSMesa) collect only the backend tests'
own files: the Makefile's list must be tests/conftest.py's, or a backend test added
elsewhere would run on EGL alone, silently; OSMesa's files are among them."""

import re

from tests.conftest import BACKEND_PATHS, ROOT


def test_the_backend_passes_collect_every_backend_test():
    make = (ROOT / "Makefile").read_text(encoding="utf-8").replace("\\\n", " ")
    listed = re.search(r"^BACKEND_TESTS := (.*)$", make, re.M).group(1).split()
    assert sorted(p.rstrip("/") for p in listed) == sorted(p.rstrip("/") for p in BACKEND_PATHS)
    assert "$(BACKEND_TESTS)" in make
    osmesa = re.search(r"^OSMESA_TESTS := (.*)$", make, re.M).group(1).split()
    assert all(any(f.startswith(p) for p in BACKEND_PATHS) for f in osmesa), osmesa
    assert all((ROOT / f).is_file() for f in osmesa) and "$(OSMESA_TESTS)" in make
