#!/usr/bin/env python3
"""Writes a held-out MovingAI map and scenario file that no bundled problem uses: OUT/rooms.map (200 x 160 cells,
walls every 40 cells with 2-cell doors, 120 random blocks) and OUT/rooms.map.scen (40 scenarios whose octile grid
distance is 60-200 cells, computed by Dijkstra as MovingAI's files give it), plus OUT/rooms.yaml, the 64room problem
pointed at them. Usage: scripts/rooms_map.py OUT [SEED]   (docs/heading-lattice.md, "A held-out map")"""
import os, random, sys

from movingai_scen import scenario_lines

out = sys.argv[1]
random.seed(int(sys.argv[2]) if len(sys.argv) > 2 else 7)
os.makedirs(out, exist_ok=True)
W, H = 200, 160
g = [['.'] * W for _ in range(H)]
for x in range(W):
    g[0][x] = g[H - 1][x] = '@'
for y in range(H):
    g[y][0] = g[y][W - 1] = '@'
for wx in range(40, W, 40):          # walls across x, three doors each
    for y in range(H):
        g[y][wx] = 'T'
    for _ in range(3):
        dy = random.randrange(5, H - 5)
        for k in range(2):
            g[dy + k][wx] = '.'
for wy in range(40, H, 40):          # walls across y, four doors each
    for x in range(W):
        if g[wy][x] == '.':
            g[wy][x] = '@'
    for _ in range(4):
        dx = random.randrange(5, W - 5)
        for k in range(2):
            g[wy][dx + k] = '.'
for _ in range(120):                 # blocks of 1-5 cells a side
    x, y = random.randrange(1, W - 6), random.randrange(1, H - 6)
    w, h = random.randrange(1, 6), random.randrange(1, 6)
    for yy in range(y, y + h):
        for xx in range(x, x + w):
            g[yy][xx] = '@'
with open(os.path.join(out, 'rooms.map'), 'w') as f:
    f.write("type octile\nheight %d\nwidth %d\nmap\n%s\n" % (H, W, "\n".join("".join(r) for r in g)))


def free(x, y):
    return 0 <= x < W and 0 <= y < H and g[y][x] in '.G'


lines = scenario_lines("rooms.map", W, H, free, free, 40, 60, 200)
with open(os.path.join(out, 'rooms.map.scen'), 'w') as f:
    f.write("\n".join(lines) + "\n")

here = os.path.dirname(os.path.abspath(__file__))
problem = open(os.path.join(here, '..', 'problems', 'movingai_64room.yaml')).read()
problem = problem.replace('name: movingai_64room', 'name: heldout_rooms')
problem = problem.replace('maps/movingai/64room_000.map.scen', os.path.abspath(os.path.join(out, 'rooms.map.scen')))
problem = problem.replace('maps/movingai/64room_000.map', os.path.abspath(os.path.join(out, 'rooms.map')))
problem = problem.replace('buckets: [40, 49]', 'buckets: [0, 100]')
problem = problem.replace("the map's extent, [0, 51.2] x [0, 51.2]", "the map's extent, [0, %g] x [0, %g]" % (W * 0.1, H * 0.1))
start = problem.index('description: >-\n')
end = problem.index('\nrobot:', start)
problem = (problem[:start] + 'description: >-\n  The 64room robot and lattice settings on a held-out map from scripts/rooms_map.py (200 x 160 cells of '
           '0.1 m, rooms with two-cell doors, random blocks), its 40 scenarios, one benchmark run per scenario.' +
           problem[end:])
# the 64room file's opening comments describe its own map: replaced by one line about this one
body = problem[problem.index('name: heldout_rooms'):]
with open(os.path.join(out, 'rooms.yaml'), 'w') as f:
    f.write('# Made by scripts/rooms_map.py from problems/movingai_64room.yaml: a map no bundled problem uses.\n' + body)
print(os.path.join(out, 'rooms.yaml'))
