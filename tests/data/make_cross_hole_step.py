"""Writes tests/data/verification/cross_hole.step with gmsh's OpenCASCADE kernel, built
from primitives (not from a shaftfem profile): a 30 mm bar, 300 mm long, a 6 mm cross
hole through its axis at 100 mm, and a circlip ring groove 1.3 mm wide and 1.2 mm deep
at 220 mm (its floor corners sharp). A verification case for STEP solids.

    .venv/bin/python tests/data/make_cross_hole_step.py
"""

from pathlib import Path

import gmsh

OUT = Path(__file__).parent / "verification" / "cross_hole.step"


def main() -> None:
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    occ = gmsh.model.occ
    bar = occ.addCylinder(0, 0, 0, 0, 0, 300, 15)
    hole = occ.addCylinder(-20, 0, 100, 40, 0, 0, 3)
    ring = occ.addCylinder(0, 0, 220 - 0.65, 0, 0, 1.3, 15)
    core = occ.addCylinder(0, 0, 220 - 0.65, 0, 0, 1.3, 15 - 1.2)
    groove, _ = occ.cut([(3, ring)], [(3, core)])
    occ.cut([(3, bar)], [(3, hole)] + groove)
    occ.synchronize()
    gmsh.option.setString("Geometry.OCCTargetUnit", "MM")
    gmsh.write(str(OUT))
    gmsh.finalize()


if __name__ == "__main__":
    main()
