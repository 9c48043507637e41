#!/usr/bin/env python3
"""Writes a held-out cave map in MovingAI's format, with issue 14's robot: OUT/cave.map (193 x 194 cells, the size of
the Dragon Age map issue 14 was filed on: a cellular-automaton cave, about 69 % free), OUT/cave.map.scen (40 scenarios
whose octile grid distance is 80-220 cells, between cells whose 8 neighbours are free, computed by Dijkstra as
MovingAI's files give it) and OUT/cave.yaml, the 64room problem pointed at them with the 0.16 m x 0.06 m rectangle of
issue 14 (same lattice parameters). Usage: scripts/cave_map.py OUT [SEED]   (docs/heading-lattice.md, "A cave map")"""
import os, random, sys

from movingai_scen import scenario_lines

out = sys.argv[1]
random.seed(int(sys.argv[2]) if len(sys.argv) > 2 else 3)
os.makedirs(out, exist_ok=True)
W, H = 193, 194
g = [['@' if random.random() < 0.45 else '.' for _ in range(W)] for _ in range(H)]
for _ in range(5):  # a cell with 5 or more blocked cells among its 3 x 3 (outside counts as blocked) becomes blocked
    n = [[sum(1 for dy in (-1, 0, 1) for dx in (-1, 0, 1)
              if not (0 <= x + dx < W and 0 <= y + dy < H) or g[y + dy][x + dx] == '@') for x in range(W)]
         for y in range(H)]
    g = [['@' if n[y][x] >= 5 else '.' for x in range(W)] for y in range(H)]
for x in range(W):
    g[0][x] = g[H - 1][x] = '@'
for y in range(H):
    g[y][0] = g[y][W - 1] = '@'


def free(x, y):
    return 0 <= x < W and 0 <= y < H and g[y][x] == '.'


def roomy(x, y):  # the robot (0.17 m across its diagonal) fits at the cell centre at some heading
    return all(free(x + dx, y + dy) for dx in (-1, 0, 1) for dy in (-1, 0, 1))


lines = scenario_lines("cave.map", W, H, free, roomy, 40, 80, 220)
with open(os.path.join(out, 'cave.map'), 'w') as f:
    f.write("type octile\nheight %d\nwidth %d\nmap\n%s\n" % (H, W, "\n".join("".join(r) for r in g)))
with open(os.path.join(out, 'cave.map.scen'), 'w') as f:
    f.write("\n".join(lines) + "\n")

here = os.path.dirname(os.path.abspath(__file__))
problem = open(os.path.join(here, '..', 'problems', 'movingai_64room.yaml')).read()
body = problem[problem.index('name: movingai_64room'):]
body = body.replace('name: movingai_64room', 'name: heldout_cave')
body = body.replace('maps/movingai/64room_000.map.scen', os.path.abspath(os.path.join(out, 'cave.map.scen')))
body = body.replace('maps/movingai/64room_000.map', os.path.abspath(os.path.join(out, 'cave.map')))
body = body.replace('buckets: [40, 49]', 'buckets: [0, 100]')
body = body.replace("the map's extent, [0, 51.2] x [0, 51.2]", "the map's extent, [0, %g] x [0, %g]" % (W * 0.1, H * 0.1))
body = body.replace('footprint: [[-0.03, -0.02], [0.03, -0.02], [0.03, 0.02], [-0.03, 0.02]]',
                    'footprint: [[-0.08, -0.03], [0.08, -0.03], [0.08, 0.03], [-0.08, 0.03]]')
start = body.index('description: >-\n')
end = body.index('\nrobot:', start)
body = (body[:start] + 'description: >-\n  Issue 14\'s 0.16 m x 0.06 m turn-in-place rectangle with the 64room lattice settings on '
        'a held-out cave map from scripts/cave_map.py (193 x 194 cells of 0.1 m), its 40 scenarios, one benchmark run '
        'per scenario.' + body[end:])
with open(os.path.join(out, 'cave.yaml'), 'w') as f:
    f.write('# Made by scripts/cave_map.py from problems/movingai_64room.yaml: a map no bundled problem uses.\n' + body)
print(os.path.join(out, 'cave.yaml'))
