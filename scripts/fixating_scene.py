#!/usr/bin/env python3
"""Views that fixate one point from one distance, as around a turntable: every pair's optical axes
meet there, where a fundamental matrix leaves the focal length free, so the mapper's view-graph
calibration cannot estimate it and a calibration pass runs (docs/benchmark-history.md, "What a
calibration pass needs"). The elevation swings as the views go round, so that the views together
still fix the focal length for bundle adjustment (one level orbit is a critical motion for it too).

  fixating_scene.py trajectory OUT --num_views N --arc_deg A --distance D --elevation_deg E
      writes a KITTI-format pose file (camera-to-world 3x4 per line) for
      `ramap synthesize --Synthetic.trajectory_path OUT`.
  fixating_scene.py unknown DATABASE --guess_factor G
      marks every camera of a COLMAP database as a user without a calibration has it: the focal
      length scaled by G, the principal point at the image's centre, prior_focal_length 0.
"""
import argparse
import math
import sqlite3
import struct


def look_at_origin(center):
    """Camera-to-world rotation (columns: camera x, y, z in the world) looking at the origin,
    image y pointing down (world -y up)."""
    z = [-c for c in center]
    norm = math.sqrt(sum(v * v for v in z))
    z = [v / norm for v in z]
    down = [0.0, 1.0, 0.0]
    x = [down[1] * z[2] - down[2] * z[1], down[2] * z[0] - down[0] * z[2],
         down[0] * z[1] - down[1] * z[0]]
    norm = math.sqrt(sum(v * v for v in x))
    x = [v / norm for v in x]
    y = [z[1] * x[2] - z[2] * x[1], z[2] * x[0] - z[0] * x[2], z[0] * x[1] - z[1] * x[0]]
    return [[x[i], y[i], z[i]] for i in range(3)]


def write_trajectory(args):
    with open(args.output, "w") as out:
        for k in range(args.num_views):
            azimuth = math.radians(args.arc_deg) * k / args.num_views
            # The elevation goes up and down twice per quarter turn's worth of views.
            elevation = math.radians(args.elevation_deg) * math.sin(2 * math.pi * k / 8)
            center = [args.distance * math.cos(elevation) * math.sin(azimuth),
                      -args.distance * math.sin(elevation),
                      args.distance * math.cos(elevation) * math.cos(azimuth)]
            rotation = look_at_origin(center)
            row = []
            for i in range(3):
                row += rotation[i] + [center[i]]
            out.write(" ".join("%.9f" % v for v in row) + "\n")


def mark_unknown(args):
    connection = sqlite3.connect(args.database)
    cameras = connection.execute("SELECT camera_id, model, width, height, params FROM cameras")
    for camera_id, model, width, height, params in cameras.fetchall():
        values = list(struct.unpack("%dd" % (len(params) // 8), params))
        # COLMAP's model ids: SIMPLE_PINHOLE 0, PINHOLE 1, SIMPLE_RADIAL 2, RADIAL 3, OPENCV 4.
        num_focal = 2 if model in (1, 4) else 1
        for i in range(num_focal):
            values[i] *= args.guess_factor
        values[num_focal] = width / 2.0
        values[num_focal + 1] = height / 2.0
        connection.execute(
            "UPDATE cameras SET params = ?, prior_focal_length = 0 WHERE camera_id = ?",
            (struct.pack("%dd" % len(values), *values), camera_id))
    connection.commit()


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    commands = parser.add_subparsers(dest="command", required=True)
    trajectory = commands.add_parser("trajectory")
    trajectory.add_argument("output")
    trajectory.add_argument("--num_views", type=int, default=36)
    trajectory.add_argument("--arc_deg", type=float, default=360.0)
    trajectory.add_argument("--distance", type=float, default=10.0)
    trajectory.add_argument("--elevation_deg", type=float, default=20.0)
    unknown = commands.add_parser("unknown")
    unknown.add_argument("database")
    unknown.add_argument("--guess_factor", type=float, default=0.5)
    args = parser.parse_args()
    if args.command == "trajectory":
        write_trajectory(args)
    else:
        mark_unknown(args)


if __name__ == "__main__":
    main()
