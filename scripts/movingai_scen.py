"""Scenario files in MovingAI's format for the held-out map scripts (rooms_map.py, cave_map.py): octile grid
distances as MovingAI computes them (Dijkstra, no corner cutting) and random start-goal pairs within a distance band.
Randomness from the caller's seeded `random` module, so a script's seed fixes its scenarios."""
import heapq, math, random


def octile_distances(free, sx, sy):
    """Grid distance from (sx, sy) to every cell reachable through cells where free(x, y) holds."""
    dist = {(sx, sy): 0.0}
    queue = [(0.0, sx, sy)]
    while queue:
        d, x, y = heapq.heappop(queue)
        if d > dist[(x, y)]:
            continue
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                nx, ny = x + dx, y + dy
                if (dx == dy == 0) or not free(nx, ny) or (dx and dy and not (free(x + dx, y) and free(x, y + dy))):
                    continue
                nd = d + (math.sqrt(2) if dx and dy else 1)
                if nd < dist.get((nx, ny), 1e18):
                    dist[(nx, ny)] = nd
                    heapq.heappush(queue, (nd, nx, ny))
    return dist


def scenario_lines(map_name, width, height, free, endpoint, count, low, high):
    """`version 1` and \\e count scenario lines: a random start where endpoint(x, y) holds, a goal drawn among the
    cells at grid distance in (low, high) from it where endpoint holds too; bucket = distance // 4."""
    lines = ["version 1"]
    while len(lines) <= count:
        sx, sy = random.randrange(width), random.randrange(height)
        if not endpoint(sx, sy):
            continue
        dist = octile_distances(free, sx, sy)
        far = [k for k, v in dist.items() if low < v < high and endpoint(*k)]
        if not far:
            continue
        gx, gy = random.choice(far)
        lines.append("%d\t%s\t%d\t%d\t%d\t%d\t%d\t%d\t%.8f" % (int(dist[(gx, gy)] // 4), map_name, width, height, sx, sy,
                                                              gx, gy, dist[(gx, gy)]))
    return lines
