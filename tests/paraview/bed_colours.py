"""Reads a PNG written by `tmdem render` and prints the hue of the spheres at the bottom and at
the top of the bed, for tests/paraview/test_paraview_render.cpp.

  /usr/bin/python3 bed_colours.py IMAGE.png
prints "bottom_hue TOP_HUE top_hue TOP_HUE bed_rows N pixels P": the median hue (degrees; reds
near 0 are taken as -30..30) of the saturated pixels in the lowest and highest 12 % of the bed's
rows. The bed is every pixel left of the colour bar (x < 80 % of the width) and below the time
label (y > 8 % of the height) that is not background white and is saturated (shaded sphere
colour; the grey force tubes, specular highlights and translucent edges drop out).
With the Turbo colour map the hue falls from about 280 (the cold end) to about 0 (the hot end),
so a bed heated from its floor, coloured over its own range, has a red bottom and a purple top.
Exit 1 when no bed pixels are found.
"""
import sys

import matplotlib.image
import numpy

image = matplotlib.image.imread(sys.argv[1])[..., :3].astype(float)  # rows from the top
if image.max() > 1.0:
    image /= 255.0
height, width, _ = image.shape
image = image[int(0.08 * height):, : int(0.8 * width)]
top = image.max(axis=2)
bottom = image.min(axis=2)
chroma = top - bottom
saturation = numpy.where(top > 0, chroma / numpy.maximum(top, 1e-12), 0.0)
bed = (saturation > 0.3) & (top > 0.08)
rows = numpy.nonzero(bed.any(axis=1))[0]
if rows.size == 0:
    print("no bed pixels")
    sys.exit(1)

r, g, b = image[..., 0], image[..., 1], image[..., 2]
safe = numpy.maximum(chroma, 1e-12)
hue = numpy.where(top == r, ((g - b) / safe) % 6.0,
                  numpy.where(top == g, (b - r) / safe + 2.0, (r - g) / safe + 4.0)) * 60.0
hue = numpy.where(hue > 330.0, hue - 360.0, hue)
first, last = rows[0], rows[-1]
band = max(1, int(0.12 * (last - first + 1)))
top_band = numpy.zeros_like(bed)
top_band[first:first + band] = True
bottom_band = numpy.zeros_like(bed)
bottom_band[last - band + 1:last + 1] = True
top_hue = numpy.median(hue[bed & top_band])
bottom_hue = numpy.median(hue[bed & bottom_band])
print(f"bottom_hue {bottom_hue:.1f} top_hue {top_hue:.1f} bed_rows {last - first + 1} "
      f"pixels {int(bed.sum())}")
