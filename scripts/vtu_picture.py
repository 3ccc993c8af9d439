#!/usr/bin/python3
"""Draws a picture from fetic's ParaView output with VTK alone (Debian's python3-vtk9),
as a check that the exported data stand on their own: the struts warped by their
displacement (magnified) and coloured by a stress array, the contact pairs as lines
coloured by their force.

usage: xvfb-run -a scripts/vtu_picture.py STRUTS.vtu CONTACTS.vtu OUT.png
           [--array stress_von_mises] [--magnification M] [--size 1200x500]
(VTK's Debian build draws through X: without a display, run it under xvfb-run.)"""

import argparse

from vtkmodules.vtkCommonCore import vtkLookupTable
from vtkmodules.vtkFiltersCore import vtkTubeFilter
from vtkmodules.vtkFiltersGeneral import vtkWarpVector
from vtkmodules.vtkFiltersGeometry import vtkGeometryFilter
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
from vtkmodules.vtkRenderingAnnotation import vtkScalarBarActor
from vtkmodules.vtkRenderingCore import (vtkActor, vtkPolyDataMapper, vtkRenderer,
                                         vtkRenderWindow, vtkWindowToImageFilter)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  (the OpenGL back end)
import vtkmodules.vtkRenderingFreeType  # noqa: F401  (text of the scalar bar)


def read(path):
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    return reader


def warped(reader, magnification):
    reader.GetOutput().GetPointData().SetActiveVectors("displacement")
    warp = vtkWarpVector()
    warp.SetInputConnection(reader.GetOutputPort())
    warp.SetScaleFactor(magnification)
    surface = vtkGeometryFilter()
    surface.SetInputConnection(warp.GetOutputPort())
    surface.warp = warp  # the warp filter lives as long as the surface
    return surface


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("struts")
    parser.add_argument("contacts")
    parser.add_argument("out")
    parser.add_argument("--array", default="stress_von_mises")
    parser.add_argument("--magnification", type=float, default=0.0)
    parser.add_argument("--size", default="1200x500")
    args = parser.parse_args()
    width, height = (int(v) for v in args.size.split("x"))

    struts = read(args.struts)
    grid = struts.GetOutput()
    bounds = grid.GetBounds()
    extent = max(bounds[1] - bounds[0], bounds[3] - bounds[2])
    displacement = grid.GetPointData().GetArray("displacement")
    largest = 1e-300
    for i in range(displacement.GetNumberOfTuples()):
        ux, uy, _ = displacement.GetTuple3(i)
        largest = max(largest, (ux * ux + uy * uy) ** 0.5)
    magnification = args.magnification or 0.05 * extent / largest

    cells = grid.GetCellData()
    array = cells.GetArray(args.array) or cells.GetArray("stress_axial")
    lut = vtkLookupTable()
    lut.SetHueRange(0.667, 0.0)
    lut.Build()
    # Keep every filter referenced: an output port does not keep its filter alive.
    strut_surface = warped(struts, magnification)
    mapper = vtkPolyDataMapper()
    mapper.SetInputConnection(strut_surface.GetOutputPort())
    mapper.SetScalarModeToUseCellFieldData()
    mapper.SelectColorArray(array.GetName())
    mapper.SetScalarRange(array.GetRange())
    mapper.SetLookupTable(lut)
    actor = vtkActor()
    actor.SetMapper(mapper)
    if grid.GetCellType(0) == 3:  # bar model: lines, drawn thick
        actor.GetProperty().SetLineWidth(6)

    contacts = read(args.contacts)
    contact_lines = warped(contacts, magnification)
    tubes = vtkTubeFilter()
    tubes.SetInputConnection(contact_lines.GetOutputPort())
    tubes.SetRadius(0.004 * extent)
    contact_mapper = vtkPolyDataMapper()
    contact_mapper.SetInputConnection(tubes.GetOutputPort())
    contact_mapper.ScalarVisibilityOff()
    contact_actor = vtkActor()
    contact_actor.SetMapper(contact_mapper)
    contact_actor.GetProperty().SetColor(0.1, 0.1, 0.1)

    bar = vtkScalarBarActor()
    bar.SetLookupTable(lut)
    bar.SetTitle(f"{array.GetName()} [Pa]")
    bar.SetNumberOfLabels(5)
    bar.SetOrientationToHorizontal()
    bar.SetPosition(0.2, 0.01)
    bar.SetWidth(0.6)
    bar.SetHeight(0.1)
    bar.GetTitleTextProperty().SetColor(0, 0, 0)
    bar.GetLabelTextProperty().SetColor(0, 0, 0)

    renderer = vtkRenderer()
    renderer.SetBackground(1, 1, 1)
    renderer.AddActor(actor)
    renderer.AddActor(contact_actor)
    renderer.AddActor2D(bar)
    renderer.ResetCamera()
    renderer.GetActiveCamera().Zoom(1.7)
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(width, height)
    window.AddRenderer(renderer)
    window.Render()
    image = vtkWindowToImageFilter()
    image.SetInput(window)
    image.Update()
    writer = vtkPNGWriter()
    writer.SetFileName(args.out)
    writer.SetInputConnection(image.GetOutputPort())
    writer.Write()
    print(f"{args.out}: {args.struts} warped x{magnification:.3g}, coloured by "
          f"{array.GetName()} ({array.GetRange()[0]:.4g} .. {array.GetRange()[1]:.4g})")


main()
