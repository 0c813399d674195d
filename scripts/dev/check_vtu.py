#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Read nceig's .vtu files with VTK's own XML reader (the one ParaView uses) and check
what a viewer needs: no reader error or warning, points and cells, every cell a valid
VTK cell whose area is positive, the cells tiling the body (their areas add up to
--area), the point data 'displacement' (3 components, finite), for hp runs the cell
data 'degree' (integers from 1 up), and the field data of a mode file (mu, mu_imag,
lambda, nu: one finite value each), which the line shows. One line per file, exit 1 if
any check fails.
Usage: /usr/bin/python3 scripts/dev/check_vtu.py [--area A] FILE.vtu ...
Needs Debian's python3-vtk9 (for /usr/bin/python3)."""
import argparse
import math
import sys

import vtk
from vtk.util.numpy_support import vtk_to_numpy


class ErrorCatcher:
    """Collects what VTK would print as an error or a warning."""

    def __init__(self):
        self.messages = []

    def __call__(self, caller, event):
        self.messages.append(event)


def check(path, area):
    problems = []
    catcher = ErrorCatcher()
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.AddObserver("ErrorEvent", catcher)
    reader.AddObserver("WarningEvent", catcher)
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    if catcher.messages:
        problems.append(f"reader: {', '.join(catcher.messages)}")
    n_points, n_cells = grid.GetNumberOfPoints(), grid.GetNumberOfCells()
    if n_points == 0 or n_cells == 0:
        problems.append(f"{n_points} points, {n_cells} cells")
        return problems, ""
    sizes = vtk.vtkCellSizeFilter()
    sizes.SetInputData(grid)
    sizes.ComputeAreaOn()
    sizes.Update()
    areas = vtk_to_numpy(sizes.GetOutput().GetCellData().GetArray("Area"))
    if not (areas > 0).all():
        problems.append(f"{int((areas <= 0).sum())} cells of area <= 0")
    total = float(areas.sum())
    if area is not None and abs(total - area) > 1e-12 * max(1.0, area):
        problems.append(f"cells' area {total!r}, expected {area!r}")
    types = {grid.GetCellType(i) for i in range(n_cells)}
    disp = grid.GetPointData().GetArray("displacement")
    if disp is None or disp.GetNumberOfComponents() != 3:
        problems.append("no point data 'displacement' of 3 components")
    elif not all(math.isfinite(x) for x in vtk_to_numpy(disp).ravel()):
        problems.append("a displacement is not finite")
    degree = grid.GetCellData().GetArray("degree")
    degrees = ""
    if degree is not None:
        d = vtk_to_numpy(degree)
        if d.min() < 1 or (d != d.round()).any():
            problems.append("cell data 'degree' not integers from 1 up")
        degrees = f", degrees {int(d.min())} to {int(d.max())}"
    fields = grid.GetFieldData()
    shown = ""
    if fields.GetNumberOfArrays() > 0:
        values = {}
        for k in range(fields.GetNumberOfArrays()):
            array = fields.GetArray(k)
            if array is None or array.GetNumberOfTuples() != 1:
                problems.append(f"field data {fields.GetArrayName(k)!r} not one value")
                continue
            values[fields.GetArrayName(k)] = array.GetValue(0)
        missing = [n for n in ("mu", "mu_imag", "lambda", "nu") if n not in values]
        if missing:
            problems.append(f"field data without {', '.join(missing)}")
        if not all(math.isfinite(v) for v in values.values()):
            problems.append("a field data value is not finite")
        shown = ", field data " + ", ".join(f"{n} = {v!r}" for n, v in values.items())
    info = (f"{n_points} points, {n_cells} cells of VTK types {sorted(types)}, "
            f"area {total:.15g}{degrees}{shown}")
    return problems, info


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--area", type=float, default=None,
                        help="the body's area, which the cells must tile")
    parser.add_argument("files", nargs="+")
    args = parser.parse_args()
    failed = False
    for path in args.files:
        problems, info = check(path, args.area)
        if problems:
            failed = True
            print(f"FAIL  {path}: {'; '.join(problems)}")
        else:
            print(f"ok    {path}: {info}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
