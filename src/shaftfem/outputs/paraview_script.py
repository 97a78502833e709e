"""Open the exported mode shapes in ParaView, already warped (copied next to modes.pvd).

In the ParaView window: View > Python Shell > Run Script, pick this file; then
step through the modes with the time controls (time = mode number). Without a
window, `pvpython open_in_paraview.py --png modes_paraview.png` saves a picture
of mode 1 (`--mode N` for another).

Every step holds the same arrays: `displacement` (the mass-normalised mode
shape, m / sqrt(kg)) and `displacement_magnitude`; its field data give the
mode number, the frequency (Hz) and the kind. Mode shapes have no physical
amplitude, so the warp is scaled for display: the largest displacement over
all modes is drawn as 6 % of the shaft's length.
"""

import sys
from pathlib import Path

from paraview.simple import (
    ColorBy,
    GetActiveViewOrCreate,
    GetAnimationScene,
    GetColorTransferFunction,
    GetScalarBar,
    PVDReader,
    Render,
    ResetCamera,
    SaveScreenshot,
    Show,
    WarpByVector,
)

DRAWN_FRACTION = 0.06


def here() -> Path:
    try:
        return Path(__file__).resolve().parent
    except NameError:  # run from the GUI's Python shell without a file name
        return Path.cwd()


def open_modes(folder: Path):
    reader = PVDReader(FileName=str(folder / "modes.pvd"))
    reader.UpdatePipelineInformation()
    steps = list(reader.TimestepValues)
    largest = 0.0
    for t in steps:
        reader.UpdatePipeline(t)
        largest = max(largest, reader.PointData["displacement_magnitude"].GetRange()[1])
    b = reader.GetDataInformation().GetBounds()
    length = max(b[1] - b[0], b[3] - b[2], b[5] - b[4])
    warp = WarpByVector(Input=reader, Vectors=["POINTS", "displacement"],
                        ScaleFactor=DRAWN_FRACTION * length / largest)
    view = GetActiveViewOrCreate("RenderView")
    undeformed = Show(reader, view)  # the shaft at rest, translucent grey
    undeformed.ColorArrayName = ["POINTS", ""]
    undeformed.AmbientColor = undeformed.DiffuseColor = [0.6, 0.6, 0.6]
    undeformed.Opacity = 0.25
    shown = Show(warp, view)
    ColorBy(shown, ("POINTS", "displacement_magnitude"))
    lut = GetColorTransferFunction("displacement_magnitude")
    lut.ApplyPreset("Viridis (matplotlib)", True)
    shown.SetScalarBarVisibility(view, True)
    bar = GetScalarBar(lut, view)
    bar.Title, bar.ComponentTitle = "displacement magnitude (mass-normalised), m/sqrt(kg)", ""
    bar.Orientation, bar.WindowLocation = "Horizontal", "Lower Center"
    bar.TitleFontSize, bar.LabelFontSize, bar.ScalarBarLength = 8, 7, 0.4
    GetAnimationScene().UpdateAnimationUsingDataTimeSteps()
    # side view: the shaft's axis (z) across the picture
    # the focal point a little below the axis leaves room for the colour bar
    middle = [(b[0] + b[1]) / 2 - 0.1 * length, (b[2] + b[3]) / 2, (b[4] + b[5]) / 2]
    view.CameraFocalPoint = middle
    view.CameraPosition = [middle[0], middle[1] - 3 * length, middle[2]]
    view.CameraViewUp = [1, 0, 0]
    view.OrientationAxesVisibility = 0
    ResetCamera(view)
    view.CameraParallelProjection = 1
    view.CameraParallelScale = 0.25 * length
    return reader, warp, view, steps


if __name__ in ("__main__", "__vtkconsole__"):
    reader, warp, view, steps = open_modes(here())
    if "--png" in sys.argv:
        mode = int(sys.argv[sys.argv.index("--mode") + 1]) if "--mode" in sys.argv else 1
        view.ViewTime = steps[mode - 1]
        Render(view)
        SaveScreenshot(sys.argv[sys.argv.index("--png") + 1], view, ImageResolution=[1600, 500])
