"""Writes examples/keyed_stepped_shaft.step with build123d (a CAD kernel front end
that shaftfem does not use), to check shaftfem's STEP import against its own parametric
profile: the stepped shaft of tests/test_profiles.py (25/35/25 mm, 40/220/40 mm, shoulder
fillets 1 mm and chamfers 0.5 mm) with a DIN 6885-1 10 x 5 mm round-ended keyway, 40 mm
long, centred 150 mm from the left end, at angle 0 (towards +x), built here from
cylinders, edge fillets and chamfers and a slot cut, not from a half-section.

Not run by the tests (build123d is not among shaftfem's dependencies):

    python -m venv /tmp/b3d && /tmp/b3d/bin/pip install build123d==0.13.0
    /tmp/b3d/bin/python tests/data/make_keyed_step.py
"""

from pathlib import Path

from build123d import (
    Align,
    BuildPart,
    BuildSketch,
    Cylinder,
    GeomType,
    Locations,
    Mode,
    Plane,
    SlotCenterToCenter,
    chamfer,
    export_step,
    extrude,
    fillet,
)

MIN = (Align.CENTER, Align.CENTER, Align.MIN)

with BuildPart() as shaft:
    Cylinder(12.5, 40, align=MIN)
    with Locations((0, 0, 40)):
        Cylinder(17.5, 220, align=MIN)
    with Locations((0, 0, 260)):
        Cylinder(12.5, 40, align=MIN)
    circles = shaft.edges().filter_by(GeomType.CIRCLE)

    def at(radius, z):
        return [e for e in circles if abs(e.radius - radius) < 1e-6
                and abs(e.center().Z - z) < 1e-6]

    fillet(at(12.5, 40) + at(12.5, 260), radius=1.0)
    circles = shaft.edges().filter_by(GeomType.CIRCLE)
    chamfer(at(17.5, 40) + at(17.5, 260), length=0.5)
    # the keyway: a 10 mm slot, 40 mm end to end, its floor 5 mm below the top (x = 12.5)
    with BuildSketch(Plane.YZ.offset(12.5)), Locations((0, 150)):
        SlotCenterToCenter(30, 10, rotation=90)
    extrude(amount=10, mode=Mode.SUBTRACT)

out = Path(__file__).resolve().parents[2] / "examples" / "keyed_stepped_shaft.step"
export_step(shaft.part, str(out))
print(out, shaft.part.volume, "mm^3")
