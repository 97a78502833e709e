"""The exported modes in real ParaView (pvpython): one Warp By Vector, every mode deforms.

ParaView is Debian's `paraview`, installed by the set-up; these tests skip, saying
so, only where it could not be installed.
"""

import json
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from shaftfem.outputs.export import export_modes

PVPYTHON = shutil.which("pvpython")
needs_paraview = pytest.mark.skipif(
    PVPYTHON is None, reason="ParaView's pvpython is not installed (Debian package paraview); "
    "scripts/setup.sh installs it where apt-get can")


@pytest.fixture(scope="module")
def exported(cylinder, tmp_path_factory):
    out = tmp_path_factory.mktemp("paraview")
    export_modes(cylinder, out)
    return out


@needs_paraview
def test_one_warp_deforms_every_mode(cylinder, exported):
    # the warp scaled so that the largest displacement is drawn as 5 % of the length
    u = cylinder.shapes_at_points()
    scale = 0.05 * cylinder.scene.shaft.length / np.linalg.norm(u, axis=2).max()
    run = subprocess.run([PVPYTHON, str(Path(__file__).with_name("paraview_steps.py")),
                          str(exported / "modes.pvd"), str(scale)],
                         capture_output=True, text=True, timeout=300)
    line = next((x for x in run.stdout.splitlines() if x.startswith("STEPS ")), None)
    assert line is not None, run.stderr[-2000:]
    steps = json.loads(line[6:])
    assert [s["time"] for s in steps] == list(range(1, cylinder.modes.count + 1))
    for s, shape in zip(steps, u):
        assert s["arrays"] == ["displacement", "displacement_magnitude"]
        moved = np.abs(np.subtract(s["warped"], s["undeformed"])).max()
        # the bounds move by about the drawn amplitude (at least a tenth of it)
        assert moved > 0.1 * scale * np.linalg.norm(shape, axis=1).max(), s


class Screen:
    """An X server of the test's own (Xvfb) for ParaView to open its window on.

    It picks a free display itself and says which when it is ready (-displayfd), so two
    started at once (a suite's workers) never race for one display as xvfb-run -a's lock
    files can; it does not reset when its last client leaves (-noreset: ParaView opens
    a test window, closes it and opens its own, and a server resetting between the two
    refuses the second, "bad X server connection"); and the display is opened once
    before ParaView is started on it."""

    def __init__(self) -> None:
        import os

        read, write = os.pipe()
        self.server = subprocess.Popen(
            ["Xvfb", "-displayfd", str(write), "-screen", "0", "1920x1080x24", "-nolisten",
             "tcp", "+extension", "GLX", "-noreset"], pass_fds=(write,),
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.close(write)
        with os.fdopen(read) as f:
            self.display = f":{f.readline().strip()}"
        self.ready = self._opens()

    def _opens(self, seconds: float = 10.0) -> bool:
        """Whether a client can open the display (XOpenDisplay), waiting up to `seconds`."""
        import ctypes
        import time

        try:
            x11 = ctypes.cdll.LoadLibrary("libX11.so.6")
        except OSError:
            return True   # no probe to be had: ParaView will say
        x11.XOpenDisplay.restype = ctypes.c_void_p
        x11.XOpenDisplay.argtypes = [ctypes.c_char_p]
        x11.XCloseDisplay.argtypes = [ctypes.c_void_p]
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            handle = x11.XOpenDisplay(self.display.encode())
            if handle:
                x11.XCloseDisplay(handle)
                return True
            time.sleep(0.1)
        return False

    def close(self) -> None:
        self.server.terminate()
        self.server.wait(timeout=30)


@needs_paraview
def test_the_exported_paraview_script_renders(exported, tmp_path):
    import os

    if shutil.which("Xvfb") is None:
        pytest.skip("Xvfb is not installed (Debian package xvfb): no screen to render on")
    png = tmp_path / "mode3.png"
    # under a loaded machine an X server has refused ParaView its OpenGL window
    # (vtkXOpenGLRenderWindow aborts before a frame is drawn); that is the screen's
    # fault, not the script's: the render is tried again on a fresh server, and each
    # retry is said as a warning
    for attempt in range(3):
        screen = Screen()
        try:
            assert screen.ready, f"Xvfb on {screen.display} takes no client"
            run = subprocess.run([PVPYTHON, "open_in_paraview.py", "--png", str(png),
                                  "--mode", "3"], cwd=exported, capture_output=True,
                                 text=True, timeout=300,
                                 env={**os.environ, "DISPLAY": screen.display})
        finally:
            screen.close()
        window = "vtkXOpenGLRenderWindow" in run.stderr or "GLX" in run.stderr
        if png.exists() or not window:
            break
        import warnings

        warnings.warn(f"ParaView could not open its window on Xvfb (try {attempt + 1}); "
                      "rendering again on a fresh server", stacklevel=1)
    assert png.exists(), run.stderr[-2000:]
    from PIL import Image

    img = np.asarray(Image.open(png).convert("RGB"))
    assert img.shape[:2] == (500, 1600)
    assert len(np.unique(img.reshape(-1, 3), axis=0)) > 100  # a shaded, coloured shaft
