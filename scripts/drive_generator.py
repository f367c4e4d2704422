#!/usr/bin/env python3
"""Writes a synthetic drive as a COLMAP 3.8 database, from a generator written apart from
`ramap synthesize` (scripts/drivegen), so that what is tuned on one generator is checked on the
other. See docs/data.md, "The second generator".

  scripts/drive_generator.py --trajectory ../shared/data/gt_trajectories/kitti_odometry_poses/06.txt \
      --output_path build/drives/kitti06 [--seed 2] [--aliased_ratio 0.10] [--num_frames 500]

Writes OUTPUT/database.db (one PINHOLE camera with its intrinsics as a prior, images
image_0/NNNNNN.png), OUTPUT/ground_truth.txt (TUM, timestamps are frame numbers, for
`ramap evaluate --ground_truth_format tum`), OUTPUT/drive.json (settings and counts) and
OUTPUT/aliased_pairs.txt. OUTPUT must not exist or be empty; it appears only when complete.
"""
import argparse
import os
import shutil
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from drivegen import trajectories  # noqa: E402
from drivegen.generate import Settings, generate  # noqa: E402


def parse_arguments():
    defaults = Settings()
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--trajectory", required=True, help="ground-truth motion file")
    parser.add_argument("--trajectory_format", choices=["kitti", "tum", "euroc_tum", "euroc_csv"],
                        help="default: from the file's name")
    parser.add_argument("--output_path", required=True)
    parser.add_argument("--layout", choices=["street", "room"],
                        help="default: street for KITTI, room for TUM and EuRoC")
    for name in ("seed", "num_frames", "stride", "overlap"):
        parser.add_argument("--" + name, type=int, default=getattr(defaults, name))
    for name in ("noise_px", "outlier_ratio", "aliased_ratio", "max_alias_deg", "translation_alias_share",
                 "loop_radius_m", "stops_per_1000", "density"):
        parser.add_argument("--" + name, type=float, default=getattr(defaults, name))
    return parser.parse_args()


def main():
    args = parse_arguments()
    kind = args.trajectory_format or trajectories.guess_kind(args.trajectory)
    camera = {"kitti": "kitti", "tum": "tum"}.get(kind, "euroc")
    layout = args.layout or ("street" if kind == "kitti" else "room")
    output = os.path.abspath(args.output_path)
    if os.path.exists(output) and (not os.path.isdir(output) or os.listdir(output)):
        sys.exit(f"drive_generator: --output_path {output}: exists and is not an empty folder")
    try:
        poses = trajectories.load(args.trajectory, kind)
        settings = Settings(seed=args.seed, layout=layout, camera=camera, num_frames=args.num_frames,
                            stride=args.stride, overlap=args.overlap, noise_px=args.noise_px,
                            outlier_ratio=args.outlier_ratio, aliased_ratio=args.aliased_ratio,
                            max_alias_deg=args.max_alias_deg,
                            translation_alias_share=args.translation_alias_share,
                            loop_radius_m=args.loop_radius_m, stops_per_1000=args.stops_per_1000,
                            density=args.density)
        os.makedirs(os.path.dirname(output) or ".", exist_ok=True)
        staging = tempfile.mkdtemp(prefix=".drivegen-", dir=os.path.dirname(output))
        try:
            summary = generate(poses, staging, settings)
            if os.path.isdir(output):
                os.rmdir(output)  # empty, checked above
            os.rename(staging, output)
        except BaseException:
            shutil.rmtree(staging, ignore_errors=True)
            raise
    except (OSError, ValueError) as error:
        sys.exit(f"drive_generator: {error}")
    print(f"drive_generator: {output}: {summary['num_frames']} frames, {summary['num_landmarks']} landmarks, "
          f"{summary['verified_pairs']} verified pairs ({summary['loop_pairs_verified']} loops, "
          f"{summary['aliased_pairs']} aliased, {summary['outlier_matches']} outlier matches), "
          f"{len(summary['stops'])} stops, {len(summary['tunnels_m'])} tunnels, "
          f"path {summary['path_length_m']:.0f} m")


if __name__ == "__main__":
    main()
