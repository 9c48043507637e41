#!/usr/bin/env python3
"""Write se2_rooms.pgm: a 20 m x 20 m floor of 4 x 4 rooms joined by doors, for michi's se2_rooms problem.

The floor is a 4 x 4 grid of rooms 5 m square (walls 0.2 m thick, on the room borders, and around the floor).
Every wall between two neighbouring rooms has a door with probability 0.6, and the doors of a spanning tree of
the rooms (a randomised depth-first search) are always there, so every room can be reached and there are loops.
Doors are 1.0 m wide, placed at a random position along the wall (at least 0.6 m from its ends). Each room holds
one random piece of furniture (a box 0.6..1.6 m by 0.4..1.2 m) kept 1.4 m away from the room's doors.
The random numbers come from a fixed linear congruential generator (seed 3, below), not Python's random module,
so the map is the same with every Python version.

Image: binary PGM (P5), 0.05 m per pixel, 400 x 400 pixels, the lower-left corner at (0, 0); row 0 is the top
(y = 20 m), as in ROS map_server images. White (255) is free, black (0) occupied. Edges are multiples of 0.05 m.

Usage: python3 make_se2_rooms_pgm.py [--out se2_rooms.pgm]
Only the Python standard library is used. Written for michi; no external data.
"""
import argparse
import os

RESOLUTION = 0.05  # metres per pixel
ROOMS = 4          # rooms per side
ROOM = 5.0         # metres, room pitch
WALL = 0.2         # metres, wall thickness
DOOR = 1.0         # metres, door width
SEED = 3


class Lcg:
    """Numerical Recipes' 32-bit linear congruential generator."""

    def __init__(self, seed):
        self.state = seed & 0xFFFFFFFF

    def uniform(self):
        self.state = (1664525 * self.state + 1013904223) & 0xFFFFFFFF
        return self.state / 2.0 ** 32

    def snapped(self, lo, hi):
        """A multiple of RESOLUTION in [lo, hi]."""
        steps = int(round((hi - lo) / RESOLUTION))
        return lo + min(steps, int(self.uniform() * (steps + 1))) * RESOLUTION


def layout():
    """Blocked rectangles (x0, x1, y0, y1) and the door openings, in metres."""
    rng = Lcg(SEED)
    size = ROOMS * ROOM
    walls = []  # (x0, x1, y0, y1)
    # the spanning tree: randomised depth-first search over the rooms
    tree = set()
    seen = {(0, 0)}
    stack = [(0, 0)]
    while stack:
        cx, cy = stack[-1]
        options = [(cx + dx, cy + dy) for dx, dy in ((1, 0), (-1, 0), (0, 1), (0, -1))
                   if 0 <= cx + dx < ROOMS and 0 <= cy + dy < ROOMS and (cx + dx, cy + dy) not in seen]
        if not options:
            stack.pop()
            continue
        nxt = options[min(len(options) - 1, int(rng.uniform() * len(options)))]
        tree.add(tuple(sorted(((cx, cy), nxt))))
        seen.add(nxt)
        stack.append(nxt)
    doors = []  # (x, y) centres
    # outer walls
    walls += [(0, size, 0, WALL), (0, size, size - WALL, size), (0, WALL, 0, size), (size - WALL, size, 0, size)]
    # inner walls with doors: vertical walls at x = k * ROOM, horizontal ones at y = k * ROOM
    for k in range(1, ROOMS):
        for r in range(ROOMS):
            for vertical in (True, False):
                pair = tuple(sorted(((k - 1, r), (k, r)) if vertical else ((r, k - 1), (r, k))))
                lo, hi = r * ROOM, (r + 1) * ROOM
                door = pair in tree or rng.uniform() < 0.6
                centre = rng.snapped(lo + WALL / 2 + 0.6 + DOOR / 2, hi - WALL / 2 - 0.6 - DOOR / 2)
                pieces = [(lo, centre - DOOR / 2), (centre + DOOR / 2, hi)] if door else [(lo, hi)]
                w0, w1 = k * ROOM - WALL / 2, k * ROOM + WALL / 2
                for a, b in pieces:
                    walls.append((w0, w1, a, b) if vertical else (a, b, w0, w1))
                if door:
                    doors.append((k * ROOM, centre) if vertical else (centre, k * ROOM))
    # furniture: one box per room, away from its doors
    for rx in range(ROOMS):
        for ry in range(ROOMS):
            for _ in range(50):
                w = rng.snapped(0.6, 1.6)
                h = rng.snapped(0.4, 1.2)
                x0 = rng.snapped(rx * ROOM + 0.6, (rx + 1) * ROOM - 0.6 - w)
                y0 = rng.snapped(ry * ROOM + 0.6, (ry + 1) * ROOM - 0.6 - h)
                near = any(x0 - 1.4 < dx < x0 + w + 1.4 and y0 - 1.4 < dy < y0 + h + 1.4 for dx, dy in doors)
                if not near:
                    walls.append((x0, x0 + w, y0, y0 + h))
                    break
    return walls, doors


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "se2_rooms.pgm"))
    args = parser.parse_args()
    walls, doors = layout()
    cells = int(round(ROOMS * ROOM / RESOLUTION))
    pixels = bytearray()
    for row in range(cells):
        y = (cells - 1 - row + 0.5) * RESOLUTION  # row 0 is the top of the image
        for col in range(cells):
            x = (col + 0.5) * RESOLUTION
            blocked = any(x0 <= x <= x1 and y0 <= y <= y1 for x0, x1, y0, y1 in walls)
            pixels.append(0 if blocked else 255)
    with open(args.out, "wb") as out:
        out.write(b"P5\n# michi se2_rooms: 0.05 m per pixel, origin (0, 0) at the lower-left corner\n")
        out.write(b"%d %d\n255\n" % (cells, cells))
        out.write(bytes(pixels))
    print("%s: %d x %d pixels, %.2f m per pixel, %d doors" % (args.out, cells, cells, RESOLUTION, len(doors)))


if __name__ == "__main__":
    main()
