#!/usr/bin/env bash
# Set up shaftfem in .venv on a fresh Debian machine: the Python packages, and the
# system libraries gmsh's wheel links against (X11/OpenGL client libraries) if any
# is missing. Safe to run again; it does nothing that is already done.
set -euo pipefail
cd "$(dirname "$0")/.."
PY=${PYTHON:-python3}
if [ ! -x .venv/bin/python ]; then
    "$PY" -m venv .venv
fi
stamp=.venv/.shaftfem-installed
if [ ! -f "$stamp" ] || [ pyproject.toml -nt "$stamp" ]; then
    .venv/bin/python -m pip install --quiet --disable-pip-version-check -e '.[test]'
    touch "$stamp"
fi
# gmsh's wheel needs libGLU, libXrender, libXcursor, libXft, libXinerama, libGL.
lib=$(ls .venv/lib/libgmsh.so* .venv/lib/python3*/site-packages/gmsh*/lib/libgmsh.so* 2>/dev/null | head -n 1 || true)
if [ -n "$lib" ] && ldd "$lib" | grep -q "not found"; then
    echo "setup: installing system libraries for gmsh" >&2
    SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
    $SUDO apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq \
        libglu1-mesa libgl1 libxrender1 libxcursor1 libxft2 libxinerama1 libx11-6 >/dev/null
fi
.venv/bin/python -c "import gmsh" || { echo "setup: gmsh does not import" >&2; exit 1; }

# Pictures: VTK renders off-screen through EGL (Mesa) when there is no display.
probe='
import os
os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
import pyvista as pv
p = pv.Plotter(off_screen=True, window_size=(64, 64))
p.add_mesh(pv.Sphere())
img = p.screenshot(return_img=True)
assert img.shape[0] == 64 and img.std() > 0
'
if ! .venv/bin/python -c "$probe" >/dev/null 2>&1; then
    echo "setup: installing system libraries for off-screen rendering" >&2
    SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
    $SUDO apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq \
        libegl1 libegl-mesa0 libgl1-mesa-dri libgbm1 libgl1 libxrender1 libx11-6 >/dev/null
    .venv/bin/python -c "$probe" >/dev/null 2>&1 || echo "setup: warning: off-screen rendering does not work; pictures will fail" >&2
fi

# ParaView (pvpython) opens the exported modes in the tests, headless; xvfb-run gives the
# exported ParaView script a screen to render on. Optional: those tests skip without them.
if ! command -v pvpython >/dev/null 2>&1 || ! command -v xvfb-run >/dev/null 2>&1; then
    echo "setup: installing ParaView and xvfb for the ParaView tests (about 440 MB)" >&2
    SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
    { $SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq paraview xvfb >/dev/null; } \
        || echo "setup: warning: could not install paraview/xvfb; the ParaView tests will skip" >&2
fi

# CalculiX (ccx) is the independent solver the tests compare with; optional.
if ! command -v ccx >/dev/null 2>&1; then
    echo "setup: installing CalculiX (calculix-ccx) for the cross-check tests" >&2
    SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
    { $SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq calculix-ccx >/dev/null; } \
        || echo "setup: warning: could not install calculix-ccx; its cross-check tests will skip" >&2
fi
