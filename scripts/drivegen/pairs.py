"""Which frames are matched, what their matches are, and how pairs go wrong.

A matched pair's correspondences are the landmarks both frames see, each kept with a probability
that falls with the change of viewing angle and of distance (descriptors match less across a wide
baseline). Pairs go wrong in three ways, all written as verified geometry, as a matcher would:
outlier matches among the inliers; aliased pairs whose matches all fit a relative pose 0-max_deg
off the truth (repeated structure), scattered and in bursts along the drive, at every frame gap;
and translation-only aliasing, whose rotation is right and whose direction of travel is not."""
import numpy as np


def skew(v):
    return np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])


def axis_angle(axis, angle_rad):
    axis = axis / np.linalg.norm(axis)
    k = skew(axis)
    return np.eye(3) + np.sin(angle_rad) * k + (1 - np.cos(angle_rad)) * k @ k


def random_axis(rng):
    v = rng.normal(size=3)
    return v / np.linalg.norm(v)


def relative_pose(pose_i, pose_j):
    """(R, t) with x_j = R x_i + t for camera-to-world poses."""
    rotation = pose_j[:3, :3].T @ pose_i[:3, :3]
    translation = pose_j[:3, :3].T @ (pose_i[:3, 3] - pose_j[:3, 3])
    return rotation, translation


def candidate_pairs(poses, overlap=10, loop_radius_m=8.0, loop_min_gap=50, loop_min_path_m=30.0,
                    loops_per_frame=2, max_axis_deg=None, rng=None):
    """Each frame with its next `overlap` frames, and loop candidates: up to loops_per_frame earlier
    frames within loop_radius_m that are at least loop_min_gap frames and loop_min_path_m of travel
    back (a revisit, not a stop). max_axis_deg (rooms) also asks the optical axes to agree."""
    n = len(poses)
    pairs = [(i, i + g) for i in range(n) for g in range(1, overlap + 1) if i + g < n]
    centres = np.array([p[:3, 3] for p in poses])
    axes = np.array([p[:3, 2] for p in poses])
    arclength = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(centres, axis=0), axis=1))])
    cell = loop_radius_m
    buckets = {}
    for index, key in enumerate(map(tuple, np.floor(centres / cell).astype(int))):
        buckets.setdefault(key, []).append(index)
    loops = 0
    for i in range(n):
        key = np.floor(centres[i] / cell).astype(int)
        near = [j for dx in (-1, 0, 1) for dy in (-1, 0, 1) for dz in (-1, 0, 1)
                for j in buckets.get((key[0] + dx, key[1] + dy, key[2] + dz), ())
                if j < i - loop_min_gap and arclength[i] - arclength[j] > loop_min_path_m]
        if not near:
            continue
        near = np.array(near)
        distance = np.linalg.norm(centres[near] - centres[i], axis=1)
        keep = distance < loop_radius_m
        if max_axis_deg is not None:
            keep &= axes[near] @ axes[i] > np.cos(np.radians(max_axis_deg))
        near, distance = near[keep], distance[keep]
        if not len(near):
            continue
        if rng is not None and max_axis_deg is not None:
            chosen = rng.choice(near, size=min(loops_per_frame, len(near)), replace=False)
        else:
            chosen = near[np.argsort(distance)[:loops_per_frame]]
        for j in chosen:
            pairs.append((int(j), i))
            loops += 1
    return pairs, loops


def true_matches(view_i, view_j, pose_i, pose_j, landmarks, rng, full_angle_deg=35.0, log_scale=0.7):
    """Keypoint index pairs (k_i, k_j) of the landmarks both frames see, each kept with probability
    0.95 exp(-(ray angle / full_angle_deg)^2 - (log distance ratio / log_scale)^2)."""
    common, a, b = np.intersect1d(view_i.sorted_landmarks, view_j.sorted_landmarks,
                                  assume_unique=True, return_indices=True)
    if not len(common):
        return np.zeros((0, 2), dtype=np.int64)
    points = landmarks.positions[common]
    ray_i = points - pose_i[:3, 3]
    ray_j = points - pose_j[:3, 3]
    dist_i = np.linalg.norm(ray_i, axis=1)
    dist_j = np.linalg.norm(ray_j, axis=1)
    cos_angle = np.einsum("ij,ij->i", ray_i, ray_j) / (dist_i * dist_j)
    angle = np.degrees(np.arccos(np.clip(cos_angle, -1, 1)))
    probability = 0.95 * np.exp(-(angle / full_angle_deg) ** 2 - (np.log(dist_i / dist_j) / log_scale) ** 2)
    kept = rng.random(len(common)) < probability
    return np.stack([view_i.sorted_keypoints[a[kept]], view_j.sorted_keypoints[b[kept]]], axis=1)


def add_outliers(matches, num_keypoints_j, ratio, rng):
    """Replace a share `ratio` of the matches' second keypoints by random ones."""
    matches = matches.copy()
    count = rng.binomial(len(matches), ratio) if len(matches) else 0
    if count:
        rows = rng.choice(len(matches), size=count, replace=False)
        matches[rows, 1] = rng.integers(0, num_keypoints_j, count)
    return matches, count


def aliased_pose(rotation, translation, rng, max_deg, translation_only):
    """A wrong relative pose: rotated 0-max_deg about a random axis (its direction of travel
    turned as far), or with translation_only, the rotation kept and the direction turned 15-90 deg."""
    scale = np.linalg.norm(translation)
    direction = translation / scale if scale > 1e-6 else random_axis(rng)
    scale = max(scale, 0.5)
    if translation_only:
        axis = np.cross(direction, random_axis(rng))
        turned = axis_angle(axis, np.radians(rng.uniform(15.0, 90.0))) @ direction
        return rotation, scale * turned
    angle = np.radians(rng.uniform(0.0, max_deg))
    wrong_rotation = axis_angle(random_axis(rng), angle) @ rotation
    turned = axis_angle(random_axis(rng), np.radians(rng.uniform(0.0, max_deg))) @ direction
    return wrong_rotation, scale * turned


def aliased_matches(view_i, view_j, pose_i, rotation, translation, landmarks, camera, rng,
                    count, noise_px, dry_run=False):
    """Matches of frame i's landmark keypoints to new keypoints of frame j where the wrong pose
    (rotation, translation) puts them: repeated structure that verifies, with ordinary noise.
    dry_run: only count how many would fall inside the image."""
    keypoints_i = view_i.sorted_keypoints
    points_world = landmarks.positions[view_i.sorted_landmarks]
    points_i = (points_world - pose_i[:3, 3]) @ pose_i[:3, :3]
    points_j = points_i @ rotation.T + translation
    front = points_j[:, 2] > 0.2
    pixels = camera.project(points_j[front])
    inside = camera.inside(pixels)
    keypoints_i, pixels = keypoints_i[front][inside], pixels[inside]
    if dry_run:
        return min(count, len(pixels))
    chosen = rng.permutation(len(pixels))[:count]
    keypoints_i = keypoints_i[chosen]
    pixels = pixels[chosen] + rng.normal(0.0, noise_px, (len(chosen), 2))
    keypoints_j = view_j.add_keypoints(pixels)
    return np.stack([keypoints_i, keypoints_j], axis=1)


def choose_aliased(pairs, num_frames, ratio, rng, burst_share=0.5, burst_frames=(15, 40), burst_rate=0.35):
    """Indices into pairs of the aliased ones: ratio of all pairs, burst_share of them in bursts
    (every pair starting in a stretch of burst_frames frames aliased with probability burst_rate),
    the rest scattered uniformly over every pair, at any frame gap."""
    target = int(round(ratio * len(pairs)))
    chosen = set()
    firsts = np.array([p[0] for p in pairs])
    burst_target = int(round(burst_share * target))
    attempts = 0
    while len(chosen) < burst_target and attempts < 1000:
        attempts += 1
        length = int(rng.integers(burst_frames[0], burst_frames[1] + 1))
        start = int(rng.integers(0, max(num_frames - length, 1)))
        inside = np.nonzero((firsts >= start) & (firsts < start + length))[0]
        for index in inside[rng.random(len(inside)) < burst_rate]:
            if len(chosen) >= burst_target:
                break
            chosen.add(int(index))
    remaining = [i for i in range(len(pairs)) if i not in chosen]
    extra = min(target - len(chosen), len(remaining))
    if extra > 0:
        chosen.update(int(i) for i in rng.choice(remaining, size=extra, replace=False))
    return chosen


def essential_and_fundamental(rotation, translation, camera):
    essential = skew(translation) @ rotation
    norm = np.linalg.norm(essential)
    if norm > 0:
        essential /= norm
    k_inverse = np.linalg.inv(camera.matrix())
    fundamental = k_inverse.T @ essential @ k_inverse
    norm = np.linalg.norm(fundamental)
    if norm > 0:
        fundamental /= norm
    return essential, fundamental
