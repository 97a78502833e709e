#!/usr/bin/env bash
# Set up shaftfem in .venv on a fresh Debian machine, exactly as locked.
#   scripts/setup.sh run    what `shaftfem design` needs: requirements/run.txt, and the
#                           X/GL and EGL client libraries gmsh and off-screen VTK link to
#   scripts/setup.sh test   the same, plus requirements/dev.txt (pytest, ruff, mypy, uv)
#                           and the independent programs the tests compare with:
#                           CalculiX (ccx), ParaView (pvpython) and xvfb
# The lock files pin every package with its hashes (`make lock` writes them); uv
# installs them with --require-hashes --no-deps, so nothing outside the lock comes in,
# and scripts/check_lock.py then compares what is installed with the lock.
# Safe to run again: a stamp holding the lock's checksum skips what is done.
set -euo pipefail
cd "$(dirname "$0")/.."
kind=${1:-run}
case "$kind" in
    run) lock=requirements/run.txt ;;
    test) lock=requirements/dev.txt ;;
    *) echo "setup: usage: scripts/setup.sh run|test" >&2; exit 2 ;;
esac
PY=${PYTHON:-python3}
SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
apt_install() {  # apt_install WHAT PACKAGE...: Debian packages, the index read once
    echo "setup: installing $1" >&2
    shift
    if [ -z "${_apt_updated:-}" ]; then $SUDO apt-get update -qq; _apt_updated=1; fi
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "$@" >/dev/null
}

if [ ! -x .venv/bin/python ]; then
    "$PY" -m venv .venv
fi
stamp=.venv/.shaftfem-$kind
sum=$(cat "$lock" pyproject.toml | sha256sum | cut -d' ' -f1)
if [ "$(cat "$stamp" 2>/dev/null)" != "$sum" ]; then
    # uv installs the lock: uv itself comes first, by pip, pinned with its hashes in
    # requirements/dev.txt like every other package. Compiled to bytecode as pip does:
    # where PYTHONDONTWRITEBYTECODE is set (this machine sets it) nothing is ever
    # compiled later, and every Python the tests start would compile numpy, SciPy and
    # VTK again (their imports 9.1 s against 1.4 s)
    pip=(.venv/bin/python -m pip --disable-pip-version-check --quiet)
    awk '/^uv==/{p=1} p{print; if ($0 !~ /\\$/) exit}' requirements/dev.txt > .venv/uv-lock.txt
    "${pip[@]}" install --require-hashes --no-deps -r .venv/uv-lock.txt
    uv=(.venv/bin/uv pip install --quiet --python .venv/bin/python --no-deps
        --compile-bytecode)
    "${uv[@]}" --require-hashes -r "$lock"
    "${uv[@]}" -e .
    .venv/bin/python scripts/check_lock.py "$lock"
    echo "$sum" > "$stamp"
fi

# gmsh's wheel needs libGLU, libXrender, libXcursor, libXft, libXinerama, libGL.
lib=$(ls .venv/lib/python3*/site-packages/gmsh*/lib/libgmsh.so* .venv/lib/libgmsh.so* 2>/dev/null | head -n 1 || true)
if [ -n "$lib" ] && ldd "$lib" | grep -q "not found"; then
    apt_install "system libraries for gmsh" \
        libglu1-mesa libgl1 libxrender1 libxcursor1 libxft2 libxinerama1 libx11-6
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
    apt_install "system libraries for off-screen rendering" \
        libegl1 libegl-mesa0 libgl1-mesa-dri libgbm1 libgl1 libxrender1 libx11-6
    .venv/bin/python -c "$probe" >/dev/null 2>&1 || echo "setup: warning: off-screen rendering does not work; pictures will fail" >&2
fi

[ "$kind" = test ] || exit 0
# The tests' independent programs: CalculiX solves the same decks, ParaView (pvpython)
# opens the exported modes headless, xvfb-run gives the ParaView script a screen, and
# Chromium opens report.html headless as a reader would.
missing=()
command -v ccx >/dev/null 2>&1 || missing+=(calculix-ccx)
command -v pvpython >/dev/null 2>&1 || missing+=(paraview)
command -v xvfb-run >/dev/null 2>&1 || missing+=(xvfb)
command -v chromium >/dev/null 2>&1 || missing+=(chromium)
if [ ${#missing[@]} -gt 0 ]; then
    apt_install "the tests' cross-check programs: ${missing[*]}" "${missing[@]}" \
        || { echo "setup: could not install ${missing[*]}" >&2; exit 1; }
fi
