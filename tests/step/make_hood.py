# A kiosk hood drawn in FreeCAD and exported as STEP, for the STEP housing tests. Run by
# `freecadcmd make_hood.py` with HOOD_STEP naming the file to write. The hood is an open-bottomed
# box 200 x 150 x 100 mm with 5 mm walls, a 120 x 80 mm window in its top and a round cable hole of
# radius 10 mm; the last line printed is its bounding box as FreeCAD measures it (JSON, mm).
import json
import os

import FreeCAD
import Part

outer = Part.makeBox(200, 150, 100)
inner = Part.makeBox(190, 140, 100, FreeCAD.Vector(5, 5, -5))
window = Part.makeBox(120, 80, 20, FreeCAD.Vector(40, 35, 90))
hole = Part.makeCylinder(10, 20, FreeCAD.Vector(20, 20, 90))
hood = outer.cut(inner).cut(window).cut(hole)
hood.exportStep(os.environ["HOOD_STEP"])
box = hood.BoundBox
print(json.dumps({"min": [box.XMin, box.YMin, box.ZMin], "max": [box.XMax, box.YMax, box.ZMax]}))
