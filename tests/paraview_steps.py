"""Run by tests/test_paraview.py under ParaView's pvpython (not by pytest itself).

    pvpython paraview_steps.py MODES.PVD SCALE

Opens the PVD, sets up one Warp By Vector on the `displacement` array at the
first step, and steps through every mode; prints, as JSON, per step the bounds
of the warped and the undeformed data and the point arrays present.
"""

import json
import sys

from paraview.simple import PVDReader, WarpByVector

reader = PVDReader(FileName=sys.argv[1])
reader.UpdatePipelineInformation()
steps = list(reader.TimestepValues)
warp = WarpByVector(Input=reader, Vectors=["POINTS", "displacement"], ScaleFactor=float(sys.argv[2]))
out = []
for t in steps:
    reader.UpdatePipeline(t)
    warp.UpdatePipeline(t)
    out.append({"time": t,
                "warped": list(warp.GetDataInformation().GetBounds()),
                "undeformed": list(reader.GetDataInformation().GetBounds()),
                "arrays": [reader.PointData.GetArray(i).GetName()
                           for i in range(len(reader.PointData))]})
print("STEPS " + json.dumps(out))
