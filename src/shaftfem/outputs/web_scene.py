"""The modes as a vtk.js scene: what report.html's 3D view shows.

The scene is VTK's own render window serialised by trame-vtk (the serialiser behind
pyvista's HTML export, used here without a server) and shown by the vtk.js viewer
trame-vtk ships. It holds, in this order: every mode's surface at its largest drawn
displacement, the surface at rest (the animation's base, hidden), the grey shaft at
rest, and the bearings and parts. report_view.js moves the shown mode's points
between the two.
"""

from __future__ import annotations

import io
import json
import zipfile
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from shaftfem.fem.result import ModalResult
    from shaftfem.outputs.render import Drawing

VIEW_SIZE = (1000, 420)


def viewer_html() -> str:
    """trame-vtk's self-contained vtk.js viewer page (about 1 MB, no network)."""
    from trame_vtk.tools.vtksz2html import HTML_VIEWER_PATH

    return Path(HTML_VIEWER_PATH).read_text(encoding="utf-8")


def mode_scene(result: ModalResult, d: Drawing | None = None) -> tuple[bytes, dict]:
    """The zipped vtk.js scene (index.json) of the modes, the shaft at rest and its
    bearings and parts, seen from the side as in modes.png; and the framing of each
    mode's view (the window's size in pixels, the camera of each mode, mm), which the
    viewer's own camera does not carry. `d`: the run's drawing, where made already (its
    coarse surface is the one drawn)."""
    from shaftfem.outputs import render

    pv = render.load_pyvista()
    # the curved faces unsubdivided: enough for a screen, a fifth the size
    d = (d or render.drawing(pv, result)).coarse
    p = render.plotter(pv, VIEW_SIZE, samples=1)
    faces = d.surface.faces
    for k in range(result.modes.count + 1):   # the modes, then the surface at rest
        mesh = pv.PolyData(d.moved(k).astype(np.float32) if k < result.modes.count
                           else np.asarray(d.surface.points, np.float32), faces)
        mesh.point_data["Normals"] = np.asarray(d.surface.point_data["Normals"], np.float32)
        mesh.point_data.active_normals_name = "Normals"
        c = (f"c{k + 1}" if k < result.modes.count else "c1")
        mesh.point_data["colour"] = np.asarray(d.surface.point_data[c], np.float32)
        p.add_mesh(mesh, scalars="colour", cmap=render.CMAP, clim=(0.0, 1.0),
                   show_scalar_bar=False)
    p.add_mesh(d.rest, color="grey", opacity=0.25)
    seats = render.draw_seats(pv, p, result.scene)
    aspect = VIEW_SIZE[0] / VIEW_SIZE[1]
    views = [render.framing(np.vstack([d.moved(k), d.moved(k, -1.0), seats]), aspect,
                            d.planes[k]) for k in range(result.modes.count)]
    render.aim(p, views[0])
    p.render()
    data = _serialised(p.render_window)
    # each mode seen across its own plane of motion, as in modes.png
    framing = {"width": VIEW_SIZE[0], "height": VIEW_SIZE[1],
               "views": [{"position": v.position.tolist(), "focus": v.focus.tolist(),
                          "up": v.up.tolist(), "parallelScale": v.parallel_scale}
                         for v in views]}
    p.close()
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr("index.json", json.dumps(data))
    return buffer.getvalue(), framing


def _serialised(render_window) -> dict:
    """A render window as the vtk.js viewer loads it: the scene's state and its arrays
    (what trame-vtk's local-rendering protocol sends a browser, written out once)."""
    from trame_vtk.modules.vtk.serializers import (
        SynchronizationContext,
        extract_array_hash,
        initialize_serializers,
        reference_id,
        serialize,
    )

    initialize_serializers()
    context = SynchronizationContext()
    context.set_ignore_last_dependencies(True)
    camera = render_window.GetRenderers().GetFirstRenderer().GetActiveCamera()
    scene = serialize(None, render_window, "shaftfem-modes", context, 1)
    scene["extra"] = {"vtkRefId": reference_id(render_window),
                      "centerOfRotation": camera.GetFocalPoint(),
                      "camera": reference_id(camera)}
    hashes = {entry["hash"]: dict(**entry, content=context.get_cached_data_array(entry["hash"]))
              for entry in extract_array_hash(scene)}
    return {"hashes": hashes, "scene": scene}
