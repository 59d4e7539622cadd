#!/usr/bin/env bash
# Run a command with a display: the current one if set, else a fresh Xvfb (xvfb-run from
# Debian's xvfb, which scripts/setup.sh installs as root). Without either the command runs
# as is, and the viewer tests report that there is no display (a failure in CI).
set -euo pipefail
if [ -n "${DISPLAY:-}" ] || [ -n "${WAYLAND_DISPLAY:-}" ]; then
    exec "$@"
elif command -v xvfb-run >/dev/null; then
    exec xvfb-run -a -s "-screen 0 1280x1024x24" "$@"
else
    echo "with-display: no DISPLAY and no xvfb-run (apt-get install xvfb)" >&2
    exec "$@"
fi
