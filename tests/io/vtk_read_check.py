"""Reads .vtk (legacy) and .vtp (XML) polydata files with VTK's own readers
and prints what they hold as one JSON object per file, one per line, for the
C++ tests to compare with what was written (tests/io/test_VtkPolyData.cpp,
tests/app/test_cli_mesh_outputs.cpp).

Usage: vtk_read_check.py FILE...
Exit 77 when VTK's Python module is missing (the tests then skip), 1 when a
reader reports an error or reads no points.

Per file: {"file", "points": [[x, y, z]...], "polys": [[a, b, c]...],
"pointData"/"cellData"/"fieldData": {NAME: {"type", "components",
"values"}}}; numbers as Python writes them (shortest exact form), non-finite
ones as the strings "nan", "inf", "-inf", strings as strings.
"""

import json
import math
import sys

try:
    from vtkmodules.vtkCommonCore import vtkCommand, vtkStringArray
    from vtkmodules.vtkIOLegacy import vtkPolyDataReader
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
except ImportError as error:
    print("VTK's Python module is not installed: %s" % error, file=sys.stderr)
    sys.exit(77)


def number(value):
    if isinstance(value, float) and not math.isfinite(value):
        return "nan" if math.isnan(value) else ("inf" if value > 0 else "-inf")
    return value


def arrays(data):
    out = {}
    for k in range(data.GetNumberOfArrays()):
        array = data.GetAbstractArray(k)
        if isinstance(array, vtkStringArray):
            values = [array.GetValue(i) for i in range(array.GetNumberOfValues())]
        else:
            values = [number(array.GetValue(i)) for i in range(array.GetNumberOfValues())]
        out[array.GetName()] = {
            "type": array.GetDataTypeAsString(),
            "components": array.GetNumberOfComponents(),
            "values": values,
        }
    return out


def read(path):
    if path.lower().endswith(".vtp"):
        reader = vtkXMLPolyDataReader()
    else:
        reader = vtkPolyDataReader()
        # ParaView reads every array of a legacy file, not only the first
        # of each kind.
        reader.ReadAllScalarsOn()
        reader.ReadAllVectorsOn()
        reader.ReadAllColorScalarsOn()
        reader.ReadAllFieldsOn()
    errors = []
    reader.AddObserver(vtkCommand.ErrorEvent, lambda obj, event: errors.append(event))
    reader.SetFileName(path)
    reader.Update()
    output = reader.GetOutput()
    if errors or output.GetNumberOfPoints() == 0:
        print("%s: VTK could not read it" % path, file=sys.stderr)
        sys.exit(1)
    points = output.GetPoints().GetData()
    polys = output.GetPolys()
    cells = []
    for c in range(output.GetNumberOfPolys()):
        ids = output.GetCell(c).GetPointIds()
        cells.append([ids.GetId(i) for i in range(ids.GetNumberOfIds())])
    return {
        "file": path,
        "pointType": points.GetDataTypeAsString(),
        "points": [list(points.GetTuple3(i)) for i in range(points.GetNumberOfTuples())],
        "cells": output.GetNumberOfCells(),
        "polys": cells if polys.GetNumberOfCells() == output.GetNumberOfCells() else [],
        "pointData": arrays(output.GetPointData()),
        "cellData": arrays(output.GetCellData()),
        "fieldData": arrays(output.GetFieldData()),
    }


for path in sys.argv[1:]:
    print(json.dumps(read(path)))
