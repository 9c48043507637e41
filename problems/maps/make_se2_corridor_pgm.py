#!/usr/bin/env python3
"""Write se2_corridor.pgm: the walls of michi's se2_corridor problem as an occupancy image.

The free space is the same as the polygon walls of problems/se2_corridor.yaml: a corridor along x
(x 0.5..6.55 m, y 1.6..2.4 m), a square room at the corner (x 6.55..8.45 m, y 1.05..2.95 m) and a corridor
along y (x 7.1..7.9 m, y 2.95..9.5 m); everything else in the 10 m x 10 m square is wall.
Image: binary PGM (P5), 0.05 m per pixel, 200 x 200 pixels, the lower-left corner at (0, 0); row 0 is the top
(y = 10 m), as in ROS map_server images. White (255) is free, black (0) occupied. All the edges above are
multiples of 0.05 m, so testing each cell's centre reproduces the polygons exactly.

Usage: python3 make_se2_corridor_pgm.py [--out se2_corridor.pgm]
Only the Python standard library is used. Written for michi; no external data.
"""
import argparse
import os

RESOLUTION = 0.05  # metres per pixel
SIZE = 10.0        # metres, square map
FREE_RECTANGLES = [  # (x min, x max, y min, y max), metres
    (0.5, 6.55, 1.6, 2.4),    # corridor along x
    (6.55, 8.45, 1.05, 2.95),  # room at the corner
    (7.1, 7.9, 2.95, 9.5),    # corridor along y
]


def occupied(x, y):
    return not any(x0 <= x <= x1 and y0 <= y <= y1 for x0, x1, y0, y1 in FREE_RECTANGLES)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                      "se2_corridor.pgm"))
    args = parser.parse_args()
    cells = int(round(SIZE / RESOLUTION))
    pixels = bytearray()
    for row in range(cells):
        y = (cells - 1 - row + 0.5) * RESOLUTION  # row 0 is the top of the image
        for col in range(cells):
            x = (col + 0.5) * RESOLUTION
            pixels.append(0 if occupied(x, y) else 255)
    with open(args.out, "wb") as out:
        out.write(b"P5\n# michi se2_corridor: 0.05 m per pixel, origin (0, 0) at the lower-left corner\n")
        out.write(b"%d %d\n255\n" % (cells, cells))
        out.write(bytes(pixels))
    print("%s: %d x %d pixels, %.2f m per pixel" % (args.out, cells, cells, RESOLUTION))


if __name__ == "__main__":
    main()
