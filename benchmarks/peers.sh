#!/usr/bin/env bash
# The peers the benchmarks measure glshade against, each in a venv of its own under .peers/
# (their pins clash with glshade's and with each other's: pyrender needs PyOpenGL 3.1.0):
# pyrender 0.1.45 (its last release), PyVista 0.49 (VTK picks EGL without a display) and
# Open3D 0.19 (open3d-cpu: 0.20 draws through Vulkan only, which llvmpipe machines lack;
# it loads libusb-1.0, installed here when run as root).
#
#     bash benchmarks/peers.sh [pyrender] [pyvista] [open3d]   # default: all three
set -euo pipefail
cd "$(dirname "$0")/.."
declare -A PINS=([pyrender]="pyrender==0.1.45" [pyvista]="pyvista==0.49.*"
                 [open3d]="open3d-cpu==0.19.0")
names=("$@")
[ ${#names[@]} -eq 0 ] && names=(pyrender pyvista open3d)
for name in "${names[@]}"; do
    pin=${PINS[$name]:-}
    if [ -z "$pin" ]; then
        echo "peers.sh: unknown peer '$name' (known: ${!PINS[*]})" >&2
        exit 2
    fi
    if [ "$name" = open3d ] && [ "$(id -u)" = 0 ] && ! ldconfig -p | grep -q libusb-1.0; then
        apt-get install -y -q libusb-1.0-0 > /dev/null
    fi
    python3 -m venv ".peers/$name"
    ".peers/$name/bin/pip" install -q "$pin"
    echo "$name: .peers/$name/bin/python ($pin)"
done
