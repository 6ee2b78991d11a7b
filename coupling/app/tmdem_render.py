"""Renders one frame of a tmdem result as a PNG: the spheres at their true size, coloured by
temperature over the range of that frame, with a colour bar "temperature (K)".

`tmdem render RESULT.h5 -o bed.png [--frame K] [--cut x|y|z] [--forces]` runs this script
through ParaView's pvbatch (on an Xvfb of its own when there is no X display). Run it
yourself with
  pvbatch tmdem_render.py RESULT.xdmf bed.png [--frame K] [--cut x|y|z] [--forces]
          [--size W H] [--colormap NAME]
(Debian 12: paraview + python3-paraview; pvbatch needs an X display:
`xvfb-run -a -s "-noreset" pvbatch ...`; without -noreset the server resets when pvbatch's
first connection closes and may drop its second).
Copy it and change what you like: it is plain paraview.simple.

- RESULT.xdmf: the file `tmdem run` writes next to RESULT.h5 (keep the two together).
- --frame K: the frame (0-based; negative counts from the end; default -1, the last).
- The camera looks horizontally at the bed along -z (y up, as under gravity [0, -g, 0]), with
  a parallel projection, so height is the image's vertical axis.
- --cut x|y|z: only the spheres whose centres lie below the bed's mid-plane normal to that axis
  are drawn, and the camera looks at the cut face (from +x for x, from +z for z, from above
  for y), so the inside of the bed shows.
- --forces: the contact network as tubes between the centres (a wall contact ends at the wall),
  tube radius growing linearly with the normal force, from 3 % of the mean sphere radius for the
  weakest contact to 30 % for the strongest; the spheres are then drawn translucent.
Exit codes: 0; 2 for a bad argument (a frame the file does not hold); 1 for anything else.
"""
import argparse
import math
import os
import sys

from paraview.simple import (CellDatatoPointData, Clip, ColorBy, ExtractBlock, ExtractSurface,
                             GetActiveViewOrCreate, GetColorTransferFunction,
                             GetOpacityTransferFunction, GetScalarBar, Glyph, Render,
                             SaveScreenshot, Show, Shrink, Text, Tube, Xdmf3ReaderT,
                             servermanager)


def fail(message, code=2):
    print(f"error: {message}", file=sys.stderr)
    sys.exit(code)


parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("xdmf", help="RESULT.xdmf, next to RESULT.h5")
parser.add_argument("png", help="the image to write (PNG)")
parser.add_argument("--frame", type=int, default=-1, help="frame (0-based; -1: the last)")
parser.add_argument("--cut", choices=["x", "y", "z"], help="cut the bed at its mid-plane")
parser.add_argument("--forces", action="store_true", help="draw the force network as tubes")
parser.add_argument("--size", type=int, nargs=2, default=[1200, 900], metavar=("W", "H"))
parser.add_argument("--colormap", default="Turbo", help="a ParaView colour map preset")
args = parser.parse_args()

# The Xdmf3 readers need an absolute path: with a bare file name they look for the .h5 at a
# wrong place ("RESULT.xdmfRESULT.h5").
path = os.path.abspath(args.xdmf)
if not os.path.isfile(path):
    fail(f"{path} does not exist (tmdem run writes it next to RESULT.h5)", 1)
result = Xdmf3ReaderT(FileName=[path])
result.UpdatePipelineInformation()
times = result.TimestepValues
try:  # a list-like property, or one number for a single time step
    times = [float(t) for t in times]
except TypeError:
    times = [float(times)]
frames = len(times)
if not -frames <= args.frame < frames:
    fail(f"{args.xdmf} has frames 0 to {frames - 1} (-1 = the last); frame {args.frame} "
         "does not exist")
frame = args.frame % frames
time = times[frame]


def leaves(data):
    """(block index, dataset) of each top-level block, for the reader's multiblock output."""
    return [(i, data.GetBlock(i)) for i in range(data.GetNumberOfBlocks())]


def arrays(data, kind):
    attributes = data.GetPointData() if kind == "point" else data.GetCellData()
    return {attributes.GetArrayName(i) for i in range(attributes.GetNumberOfArrays())}


def first_leaf(data):
    while data is not None and (data.IsA("vtkMultiBlockDataSet") or data.IsA("vtkMultiPieceDataSet")):
        count = data.GetNumberOfBlocks() if data.IsA("vtkMultiBlockDataSet") else data.GetNumberOfPieces()
        nxt = None
        for i in range(count):
            block = data.GetBlock(i) if data.IsA("vtkMultiBlockDataSet") else data.GetPiece(i)
            if block is not None:
                nxt = block
                break
        data = nxt
    return data


# Which block holds the particles (point array "id") and which the contacts (cell array
# "normal_force"): Block0 and Block1 when the file has contacts (paraview.md).
result.UpdatePipeline(time)
tree = servermanager.Fetch(result)
particle_block = contact_block = None
for index, block in leaves(tree):
    leaf = first_leaf(block)
    if leaf is None:
        continue
    if particle_block is None and "id" in arrays(leaf, "point"):
        particle_block, grains = index, leaf
    elif contact_block is None and "normal_force" in arrays(leaf, "cell"):
        contact_block, lines = index, leaf
if particle_block is None:
    fail(f"{args.xdmf}: no particle block at t = {time} s", 1)

T_min, T_max = grains.GetPointData().GetArray("temperature").GetRange()
r_min, r_max = grains.GetPointData().GetArray("radius").GetRange()
r_mean = 0.5 * (r_min + r_max)
x0, x1, y0, y1, z0, z1 = grains.GetBounds()
bounds = [x0 - r_max, x1 + r_max, y0 - r_max, y1 + r_max, z0 - r_max, z1 + r_max]
centre = [0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]), 0.5 * (bounds[4] + bounds[5])]
print(f"frame {frame} of 0..{frames - 1}, t = {time:g} s: {grains.GetNumberOfPoints()} particles, "
      f"temperature {T_min:.6g} to {T_max:.6g} K")

axes = {"x": 0, "y": 1, "z": 2}
particles = ExtractBlock(Input=result, Selectors=[f"/Root/Block{particle_block}"])
kept = particles
if args.cut:
    # Whole spheres below the mid-plane: clip the centres (one vertex each), not the glyphs.
    normal = [0.0, 0.0, 0.0]
    normal[axes[args.cut]] = 1.0
    kept = Clip(Input=particles, ClipType="Plane")
    kept.ClipType.Origin = centre
    kept.ClipType.Normal = normal
    kept.Invert = 1  # keep the side the normal points away from: below the plane
    kept.Crinkleclip = 0

# The sphere glyph has radius 0.5: scale factor 2 x radius gives each sphere its true size.
spheres = Glyph(Input=kept, GlyphType="Sphere")
spheres.ScaleArray = ["POINTS", "radius"]
spheres.ScaleFactor = 2.0
spheres.GlyphMode = "All Points"
spheres.OrientationArray = ["POINTS", "No orientation array"]
spheres.GlyphType.ThetaResolution = 24
spheres.GlyphType.PhiResolution = 16

view = GetActiveViewOrCreate("RenderView")
view.ViewSize = list(args.size)
view.ViewTime = time
view.UseColorPaletteForBackground = 0
view.Background = [1.0, 1.0, 1.0]
view.OrientationAxesVisibility = 0

display = Show(spheres, view)
ColorBy(display, ("POINTS", "temperature"))
display.Specular = 0.2
# The colour range is the chosen frame's, fixed: not t = 0's, not rescaled when time changes.
low, high = (T_min, T_max) if T_max - T_min > 1e-9 * max(1.0, abs(T_max)) else (T_min - 0.5, T_max + 0.5)
lut = GetColorTransferFunction("temperature")
lut.ApplyPreset(args.colormap, True)
lut.AutomaticRescaleRangeMode = "Never"
lut.RescaleTransferFunction(low, high)
GetOpacityTransferFunction("temperature").RescaleTransferFunction(low, high)
display.SetScalarBarVisibility(view, True)
bar = GetScalarBar(lut, view)
bar.Title = "temperature (K)"
bar.ComponentTitle = ""
bar.TitleColor = [0.0, 0.0, 0.0]
bar.LabelColor = [0.0, 0.0, 0.0]
fonts = min(args.size[0] / 1200.0, args.size[1] / 900.0)  # text scales with the image
bar.TitleFontSize = max(8, round(20 * fonts))
bar.LabelFontSize = max(8, round(18 * fonts))
bar.TitleBold = 1
bar.ScalarBarThickness = max(8, round(24 * fonts))
bar.ScalarBarLength = 0.6
bar.WindowLocation = "Any Location"
bar.Orientation = "Vertical"
bar.Position = [0.85, 0.2]
bar.AutomaticLabelFormat = 0
bar.LabelFormat = "%.1f" if high - low < 20 else "%.0f"
bar.RangeLabelFormat = "%.2f" if high - low < 20 else "%.1f"
bar.AddRangeLabels = 1
bar.DrawTickMarks = 1

if args.forces:
    display.Opacity = 0.25
    if contact_block is None or lines.GetNumberOfCells() == 0:
        print(f"frame {frame}: no contacts to draw")
    else:
        contacts = ExtractBlock(Input=result, Selectors=[f"/Root/Block{contact_block}"])
        if args.cut:
            cut_lines = Clip(Input=contacts, ClipType="Plane")
            cut_lines.ClipType.Origin = centre
            cut_lines.ClipType.Normal = normal
            cut_lines.Invert = 1
            contacts = cut_lines
        # Shrink with factor 1 gives each line its own two points, so the force (a cell value)
        # becomes the value of both its points, not an average over a sphere's contacts.
        own = Shrink(Input=contacts, ShrinkFactor=1.0)
        on_points = CellDatatoPointData(Input=own)
        surface = ExtractSurface(Input=on_points)
        F_min, F_max = lines.GetCellData().GetArray("normal_force").GetRange()
        tubes = Tube(Input=surface)
        tubes.Scalars = ["POINTS", "normal_force"]
        tubes.NumberofSides = 12
        tubes.Radius = 0.03 * r_mean
        tubes.VaryRadius = "By Scalar" if F_max > F_min else "Off"
        tubes.RadiusFactor = 10.0
        tube_display = Show(tubes, view)
        ColorBy(tube_display, None)
        tube_display.AmbientColor = tube_display.DiffuseColor = [0.15, 0.15, 0.15]
        print(f"{lines.GetNumberOfCells()} contacts, normal force {F_min:.4g} to {F_max:.4g} N")

label = Text(Text=f"t = {time:g} s (frame {frame} of 0..{frames - 1})"
             + (f", cut at {args.cut} = {centre[axes[args.cut]]:.4g} m" if args.cut else ""))
label_display = Show(label, view)
label_display.Color = [0.0, 0.0, 0.0]
label_display.FontSize = max(8, round(18 * fonts))
label_display.WindowLocation = "Upper Left Corner"

# Camera: parallel projection, looking horizontally along -z (or along -x for a cut normal to
# x, down for a cut normal to y), the bed left of the colour bar.
direction, up = [0.0, 0.0, 1.0], [0.0, 1.0, 0.0]
if args.cut == "x":
    direction = [1.0, 0.0, 0.0]
elif args.cut == "y":
    direction, up = [0.0, 1.0, 0.0], [0.0, 0.0, -1.0]
right = [up[1] * direction[2] - up[2] * direction[1], up[2] * direction[0] - up[0] * direction[2],
         up[0] * direction[1] - up[1] * direction[0]]
extent = [bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4]]
width = sum(abs(r) * e for r, e in zip(right, extent))
height = sum(abs(u) * e for u, e in zip(up, extent))
depth = sum(abs(d) * e for d, e in zip(direction, extent))
aspect = args.size[0] / args.size[1]
usable = 0.78  # share of the image width left of the colour bar
scale = max(0.55 * height / 0.9, 0.5 * width / (usable * aspect) * 1.05)  # half the view's height
shift = (0.5 - 0.5 * usable + 0.01) * 2.0 * scale * aspect  # the bed's centre to the left
focal = [c + shift * r for c, r in zip(centre, right)]
Render(view)  # the first render resets the camera: place it afterwards
view.CameraParallelProjection = 1
view.CameraFocalPoint = focal
view.CameraPosition = [f + (depth + 10.0 * max(width, height)) * d for f, d in zip(focal, direction)]
view.CameraViewUp = up
view.CameraParallelScale = scale
Render(view)
SaveScreenshot(args.png, view, ImageResolution=list(args.size), TransparentBackground=0)
print(f"wrote {args.png}")
