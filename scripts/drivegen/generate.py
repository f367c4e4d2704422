"""The whole drive: motion, landmarks, views, pairs, written as a COLMAP database with its truth."""
import json
import os

import numpy as np

from . import landmarks as landmark_layouts
from . import pairs as pair_geometry
from .colmap_db import Database
from .observations import Camera, observe
from .trajectories import insert_stops, matrix_to_quaternion

# Intrinsics of each motion's own camera (KITTI image_0, TUM fr1/fr2 RGB, EuRoC cam0), undistorted.
CAMERAS = {
    "kitti": Camera(1241, 376, 718.856, 718.856, 607.19, 185.2),
    "tum": Camera(640, 480, 517.3, 516.5, 318.6, 255.3),
    "euroc": Camera(752, 480, 458.654, 457.296, 367.215, 248.375),
}


class Settings:
    """Defaults are the floor the sequences issue sets: 0.7 px noise, 2% outlier matches, 3%
    aliased pairs at 0-40 deg, loop candidates only within 8 m of a revisit."""

    def __init__(self, **values):
        self.seed = 1
        self.layout = "street"           # street (drives) or room (hand-held, MAV)
        self.camera = "kitti"
        self.num_frames = 0              # 0: every frame of the motion (after the stride)
        self.stride = 1                  # keep every stride-th pose of the motion
        self.noise_px = 0.7              # keypoint noise, standard deviation per coordinate
        self.outlier_ratio = 0.02        # share of a verified pair's matches that are wrong
        self.aliased_ratio = 0.03        # share of the matched pairs that are aliased
        self.max_alias_deg = 40.0        # aliased rotations are 0-max_alias_deg off
        self.translation_alias_share = 0.2  # of the aliased pairs, those with the rotation right
        self.overlap = 10                # each frame matched with its next `overlap` frames
        self.loop_radius_m = 8.0         # loop candidates only where a place is revisited within this
        self.stops_per_1000 = 2.0        # stops inserted per 1000 frames (streets only)
        self.density = 1.0               # scales every landmark count
        self.min_inliers = 15            # fewer verified matches: the pair is matched, not verified
        for key, value in values.items():
            if not hasattr(self, key):
                raise ValueError(f"unknown setting '{key}'")
            setattr(self, key, value)


def _select_frames(poses, settings):
    poses = poses[::max(1, settings.stride)]
    if settings.num_frames:
        if settings.num_frames > len(poses):
            raise ValueError(f"{settings.num_frames} frames asked for, the motion has {len(poses)}")
        poses = poses[:settings.num_frames]
    if len(poses) < 3:
        raise ValueError("a drive needs at least 3 frames")
    return poses


def _write_ground_truth(path, poses):
    with open(path, "w") as out:
        out.write("# drivegen ground truth: timestamp (= frame number) tx ty tz qx qy qz qw (camera-to-world)\n")
        for index, pose in enumerate(poses):
            qw, qx, qy, qz = matrix_to_quaternion(pose[:3, :3])
            t = pose[:3, 3]
            out.write(f"{index} {t[0]:.9f} {t[1]:.9f} {t[2]:.9f} {qx:.12f} {qy:.12f} {qz:.12f} {qw:.12f}\n")


def _alias(view_i, view_j, pose_i, rotation, translation, scene, camera, rng, settings,
           num_true_matches):
    """An aliased pair's wrong pose and its matches: (rotation, translation, matches,
    translation_only)."""
    translation_only = rng.random() < settings.translation_alias_share
    count = max(num_true_matches, int(rng.integers(30, 121)))
    # A wrong pose that turns the view out of the image aliases nothing: draw again.
    for _ in range(20):
        wrong_rotation, wrong_translation = pair_geometry.aliased_pose(
            rotation, translation, rng, settings.max_alias_deg, translation_only)
        num_inside = pair_geometry.aliased_matches(view_i, view_j, pose_i, wrong_rotation,
                                                   wrong_translation, scene, camera, rng, count,
                                                   settings.noise_px, dry_run=True)
        if num_inside >= settings.min_inliers:
            break
    matches = pair_geometry.aliased_matches(view_i, view_j, pose_i, wrong_rotation, wrong_translation,
                                            scene, camera, rng, count, settings.noise_px)
    return wrong_rotation, wrong_translation, matches, translation_only


def generate(poses, output_dir, settings):
    """Writes database.db, ground_truth.txt, drive.json and aliased_pairs.txt into output_dir
    (which must exist and be empty). Returns drive.json's content."""
    rng = np.random.default_rng(settings.seed)
    camera = CAMERAS[settings.camera]
    poses = _select_frames(list(poses), settings)
    stops = []
    if settings.layout == "street":
        poses, stops = insert_stops(poses, rng, settings.stops_per_1000)
        scene, tunnels = landmark_layouts.street(poses, rng, settings.density)
    elif settings.layout == "room":
        scene, tunnels = landmark_layouts.room(poses, rng, settings.density)
    else:
        raise ValueError(f"unknown layout '{settings.layout}' (street or room)")
    views = observe(poses, scene, camera, rng, noise_px=settings.noise_px)
    candidates, num_loop_candidates = pair_geometry.candidate_pairs(
        poses, overlap=settings.overlap, loop_radius_m=settings.loop_radius_m,
        max_axis_deg=60.0 if settings.layout == "room" else None,
        # A hand-held camera revisits its room after a few steps; a car after a block or more.
        loop_min_path_m=1.0 if settings.layout == "room" else 30.0, rng=rng)
    aliased = pair_geometry.choose_aliased(candidates, len(poses), settings.aliased_ratio, rng)

    database = Database(os.path.join(output_dir, "database.db"))
    camera_id = database.add_camera(camera)
    image_ids = [database.add_image(f"image_0/{index:06d}.png", camera_id) for index in range(len(poses))]
    counts = {"matched_pairs": 0, "verified_pairs": 0, "loop_pairs_verified": 0, "aliased_pairs": 0,
              "translation_aliased_pairs": 0, "outlier_matches": 0, "inlier_matches": 0}
    alias_lines = []
    for index, (i, j) in enumerate(candidates):
        rotation, translation = pair_geometry.relative_pose(poses[i], poses[j])
        matches = pair_geometry.true_matches(views[i], views[j], poses[i], poses[j], scene, rng)
        if index in aliased:
            true_rotation = rotation
            rotation, translation, matches, translation_only = _alias(
                views[i], views[j], poses[i], rotation, translation, scene, camera, rng, settings,
                len(matches))
            if len(matches) >= settings.min_inliers:
                off = np.degrees(np.arccos(np.clip((np.trace(rotation @ true_rotation.T) - 1) / 2, -1, 1)))
                alias_lines.append(f"{image_ids[i]} {image_ids[j]} {off:.2f} "
                                   f"{'translation' if translation_only else 'rotation'}")
                counts["aliased_pairs"] += 1
                counts["translation_aliased_pairs"] += int(translation_only)
        if not len(matches):
            continue
        inliers, num_outliers = pair_geometry.add_outliers(matches, views[j].num_keypoints(),
                                                           settings.outlier_ratio, rng)
        # The raw matches also hold what verification threw out: 10% more random pairs.
        rejected = np.stack([rng.integers(0, len(views[i].pixels), len(inliers) // 10 + 1),
                             rng.integers(0, len(views[j].pixels), len(inliers) // 10 + 1)], axis=1)
        database.add_matches(image_ids[i], image_ids[j], np.vstack([inliers, rejected]))
        counts["matched_pairs"] += 1
        if len(inliers) < settings.min_inliers:
            continue
        essential, fundamental = pair_geometry.essential_and_fundamental(rotation, translation, camera)
        database.add_two_view_geometry(image_ids[i], image_ids[j], inliers, essential, fundamental)
        counts["verified_pairs"] += 1
        counts["loop_pairs_verified"] += int(j - i > settings.overlap)
        counts["outlier_matches"] += num_outliers
        counts["inlier_matches"] += len(inliers)
    for view, image_id in zip(views, image_ids):
        database.add_keypoints(image_id, view.all_pixels(), rng)
    database.close()

    _write_ground_truth(os.path.join(output_dir, "ground_truth.txt"), poses)
    with open(os.path.join(output_dir, "aliased_pairs.txt"), "w") as out:
        out.write("# image_id1 image_id2 rotation_off_deg kind\n")
        out.write("".join(line + "\n" for line in alias_lines))
    centres = np.array([p[:3, 3] for p in poses])
    observations = [int((v.landmark >= 0).sum()) for v in views]
    summary = {
        "generator": "drivegen",
        "settings": vars(settings),
        "num_frames": len(poses),
        "path_length_m": float(np.linalg.norm(np.diff(centres, axis=0), axis=1).sum()),
        "num_landmarks": len(scene),
        "landmarks_by_kind": {name: int((scene.kinds == k).sum())
                              for k, name in enumerate(landmark_layouts.KIND_NAMES) if (scene.kinds == k).any()},
        "observations_per_frame": {"min": min(observations), "median": float(np.median(observations)),
                                   "max": max(observations)},
        "candidate_pairs": len(candidates),
        "aliased_share_of_verified": counts["aliased_pairs"] / max(counts["verified_pairs"], 1),
        "loop_candidates": num_loop_candidates,
        "stops": [{"first_frame": a, "num_frames": b} for a, b in stops],
        "tunnels_m": [[round(a, 1), round(b, 1)] for a, b in tunnels],
        **counts,
    }
    with open(os.path.join(output_dir, "drive.json"), "w") as out:
        json.dump(summary, out, indent=1)
    return summary
