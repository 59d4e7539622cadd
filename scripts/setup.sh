#!/usr/bin/env bash
# Create or reuse .venv and install glshade; as root, also the Debian packages a run needs.
#   scripts/setup.sh demo   glshade alone, and Mesa's EGL and OSMesa (what a render needs)
#   scripts/setup.sh        (or "test") with its test extras, and what the window and browser
#                           tests need too: xvfb, chromium and chromium-driver
# Safe to run again.
set -euo pipefail
cd "$(dirname "$0")/.."
VENV=${VENV:-.venv}
PYTHON=${PYTHON:-python3}
KIND=${1:-test}
case "$KIND" in
    demo) EXTRAS="" ;;
    test) EXTRAS="[test]" ;;
    *) echo "setup: unknown kind '$KIND' (demo or test)" >&2; exit 2 ;;
esac

need_apt=()
if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
    ldconfig -p 2>/dev/null | grep -q 'libOSMesa.so' || need_apt+=(libosmesa6)
    ldconfig -p 2>/dev/null | grep -q 'libEGL_mesa.so' || need_apt+=(libegl-mesa0 libgl1-mesa-dri)
    if [ "$KIND" = test ]; then
        command -v Xvfb >/dev/null || need_apt+=(xvfb)
        # the notebook viewer's browser test: headless Chromium and its WebDriver
        command -v chromium >/dev/null || need_apt+=(chromium)
        command -v chromedriver >/dev/null || need_apt+=(chromium-driver)
    fi
    if [ ${#need_apt[@]} -gt 0 ]; then
        echo "setup: installing ${need_apt[*]}" >&2
        (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq \
            --no-install-recommends "${need_apt[@]}") >/dev/null \
            || echo "setup: warning: could not install ${need_apt[*]}" >&2
    fi
fi

if [ ! -x "$VENV/bin/python" ]; then
    "$PYTHON" -m venv "$VENV"
fi
stamp="$VENV/.glshade-installed-$KIND"
if [ "$KIND" = demo ] && [ -f "$VENV/.glshade-installed-test" ] \
        && ! [ pyproject.toml -nt "$VENV/.glshade-installed-test" ]; then
    stamp="$VENV/.glshade-installed-test"  # (the test install holds the demo's)
fi
if [ ! -f "$stamp" ] || [ pyproject.toml -nt "$stamp" ]; then
    # uv, the standard fast installer, resolves and unpacks the test extras in seconds (pip:
    # about a minute), compiling the bytecode as pip does (else a package's first import
    # compiles it, and its compile warnings reach a command's stderr); pip does it alone
    # where uv cannot be had. (pip's warnings about this machine's unreachable extra
    # indexes are filtered out.)
    pip=("$VENV/bin/python" -m pip install -q --disable-pip-version-check)
    if "${pip[@]}" "uv>=0.4" 2> >(grep -v "Location .* is ignored" >&2) \
            && "$VENV/bin/python" -m uv pip install -q --python "$VENV/bin/python" \
                --compile-bytecode -e ".$EXTRAS"; then
        :
    elif ! "${pip[@]}" -e ".$EXTRAS" 2> >(grep -v "Location .* is ignored" >&2); then
        echo "setup: pip install failed" >&2
        exit 1
    fi
    touch "$stamp"
fi
