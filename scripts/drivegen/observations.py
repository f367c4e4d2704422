"""What each frame sees: landmarks in view, in range and facing it, detected with a probability
that falls in fast turns (motion blur), as keypoints with pixel noise, among clutter keypoints that
match nothing."""
import numpy as np


class Camera:
    def __init__(self, width, height, fx, fy, cx, cy):
        self.width, self.height = width, height
        self.fx, self.fy, self.cx, self.cy = fx, fy, cx, cy

    def matrix(self):
        return np.array([[self.fx, 0, self.cx], [0, self.fy, self.cy], [0, 0, 1.0]])

    def project(self, points_camera):
        z = points_camera[:, 2]
        return np.stack([self.fx * points_camera[:, 0] / z + self.cx,
                         self.fy * points_camera[:, 1] / z + self.cy], axis=1)

    def inside(self, pixels, margin=4.0):
        return ((pixels[:, 0] >= margin) & (pixels[:, 0] < self.width - margin) &
                (pixels[:, 1] >= margin) & (pixels[:, 1] < self.height - margin))


class FrameView:
    """One frame's keypoints. landmark[k] is the landmark keypoint k sees (-1: clutter)."""

    def __init__(self, pixels, landmark):
        self.pixels = pixels
        self.landmark = landmark
        order = np.argsort(landmark)
        seen = landmark[order] >= 0
        self.sorted_landmarks = landmark[order][seen]
        self.sorted_keypoints = order[seen]
        self.extra_pixels = []  # keypoints added later (the aliased pairs' matches)

    def num_keypoints(self):
        return len(self.pixels) + sum(len(p) for p in self.extra_pixels)

    def add_keypoints(self, pixels):
        first = self.num_keypoints()
        self.extra_pixels.append(pixels)
        return np.arange(first, first + len(pixels))

    def all_pixels(self):
        return np.vstack([self.pixels] + self.extra_pixels) if self.extra_pixels else self.pixels


class _Grid:
    def __init__(self, positions, cell):
        self.cell = cell
        keys = np.floor(positions / cell).astype(np.int64)
        self.buckets = {}
        for index, key in enumerate(map(tuple, keys)):
            self.buckets.setdefault(key, []).append(index)
        self.buckets = {k: np.array(v) for k, v in self.buckets.items()}

    def near(self, centre, radius):
        low = np.floor((centre - radius) / self.cell).astype(int)
        high = np.floor((centre + radius) / self.cell).astype(int)
        found = [self.buckets[(x, y, z)]
                 for x in range(low[0], high[0] + 1)
                 for y in range(low[1], high[1] + 1)
                 for z in range(low[2], high[2] + 1) if (x, y, z) in self.buckets]
        return np.concatenate(found) if found else np.zeros(0, dtype=int)


def turn_rates_deg(poses):
    """Rotation between each frame and the next, in degrees (the last frame repeats its rate)."""
    rates = []
    for a, b in zip(poses[:-1], poses[1:]):
        r = a[:3, :3].T @ b[:3, :3]
        rates.append(np.degrees(np.arccos(np.clip((np.trace(r) - 1) / 2, -1, 1))))
    rates.append(rates[-1] if rates else 0.0)
    return np.array(rates)


def observe(poses, landmarks, camera, rng, noise_px=0.7, detection=0.85, blur_turn_deg=8.0,
            max_facing_deg=75.0, clutter_ratio=0.15):
    """Each frame's FrameView. A landmark is seen when it is in front, inside the image, within its
    own range and (where it has a normal) faces the camera within max_facing_deg; each is then
    detected with probability detection / (1 + (turn rate / blur_turn_deg)^2)."""
    grid = _Grid(landmarks.positions, cell=max(10.0, float(np.median(landmarks.ranges))))
    max_range = float(landmarks.ranges.max()) if len(landmarks) else 0.0
    cos_facing = np.cos(np.radians(max_facing_deg))
    rates = turn_rates_deg(poses)
    views = []
    for pose, rate in zip(poses, rates):
        centre, rotation = pose[:3, 3], pose[:3, :3]
        candidates = grid.near(centre, max_range)
        offsets = landmarks.positions[candidates] - centre
        distance = np.linalg.norm(offsets, axis=1)
        keep = (distance < landmarks.ranges[candidates]) & (distance > 1e-3)
        normals = landmarks.normals[candidates]
        has_normal = np.any(normals != 0, axis=1)
        facing = -np.einsum("ij,ij->i", normals, offsets) / np.maximum(distance, 1e-9)
        keep &= ~has_normal | (facing > cos_facing)
        candidates, offsets = candidates[keep], offsets[keep]
        in_camera = offsets @ rotation  # rows: R^T (X - C)
        front = in_camera[:, 2] > 0.2
        candidates, in_camera = candidates[front], in_camera[front]
        pixels = camera.project(in_camera)
        inside = camera.inside(pixels)
        candidates, pixels = candidates[inside], pixels[inside]
        detected = rng.random(len(candidates)) < detection / (1.0 + (rate / blur_turn_deg) ** 2)
        candidates, pixels = candidates[detected], pixels[detected]
        pixels = pixels + rng.normal(0.0, noise_px, pixels.shape)
        num_clutter = rng.poisson(clutter_ratio * len(candidates) + 5)
        clutter = np.stack([rng.uniform(4, camera.width - 4, num_clutter),
                            rng.uniform(4, camera.height - 4, num_clutter)], axis=1)
        all_pixels = np.vstack([pixels, clutter])
        landmark = np.concatenate([candidates, np.full(num_clutter, -1)])
        shuffle = rng.permutation(len(landmark))
        views.append(FrameView(all_pixels[shuffle], landmark[shuffle].astype(np.int64)))
    return views
