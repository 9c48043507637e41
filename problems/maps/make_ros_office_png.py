#!/usr/bin/env python3
"""Writes problems/maps/ros/office.png, the image of problems/maps/ros/office.yaml (a ROS map_server map).

A made-up 8 m x 6 m office at 0.05 m per pixel (160 x 120 pixels), drawn the way ROS SLAM tools save maps:
black walls (0), white free space (254) and grey unknown space (205) beyond the outer wall's gap and in a
storeroom nobody mapped. Two rooms on a corridor, doors 0.9 m wide. Only the standard library (zlib) is used, so
every Python writes the same bytes: python3 problems/maps/make_ros_office_png.py
"""
import os
import struct
import zlib

W, H = 160, 120  # pixels; 0.05 m each
FREE, WALL, UNKNOWN = 254, 0, 205


def main():
    img = [[FREE] * W for _ in range(H)]  # row 0 is the top of the map (largest y)

    def rect(x0, y0, x1, y1, v):
        # metres, map frame (y up); pixels whose centres lie inside
        for r in range(H):
            y = (H - 1 - r + 0.5) * 0.05
            if not (y0 <= y <= y1):
                continue
            for c in range(W):
                x = (c + 0.5) * 0.05
                if x0 <= x <= x1:
                    img[r][c] = v

    # unknown margin outside the building, then the outer walls (0.1 m)
    rect(0.0, 0.0, 8.0, 6.0, UNKNOWN)
    rect(0.2, 0.2, 7.8, 5.8, WALL)
    rect(0.3, 0.3, 7.7, 5.7, FREE)
    # corridor along the bottom (y 0.3 .. 1.8), wall above it with two doors
    rect(0.3, 1.8, 7.7, 1.9, WALL)
    rect(1.5, 1.8, 2.4, 1.9, FREE)   # door of room A
    rect(5.3, 1.8, 6.2, 1.9, FREE)   # door of room B
    # the wall between rooms A (x < 4) and B (x > 4.1)
    rect(4.0, 1.9, 4.1, 5.7, WALL)
    # a desk in each room, and an unmapped storeroom in room B's corner
    rect(1.0, 3.8, 2.6, 4.6, WALL)
    rect(5.2, 3.0, 6.0, 3.6, WALL)
    rect(6.6, 4.6, 7.7, 5.7, UNKNOWN)

    raw = b"".join(b"\x00" + bytes(row) for row in img)

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", W, H, 8, 0, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "ros", "office.png")
    with open(out, "wb") as f:
        f.write(png)
    print("wrote", out)


if __name__ == "__main__":
    main()
