"""Where the landmarks are: streets for the drives, rooms for the hand-held and MAV motions.

Each landmark has a position, a unit normal (zero where it is seen from every side, as a pole or
a tree) and a visibility range of its own, so that tracks have lengths of their own too."""
import numpy as np


class Landmarks:
    def __init__(self, positions, normals, ranges, kinds):
        self.positions = np.asarray(positions, dtype=float).reshape(-1, 3)
        self.normals = np.asarray(normals, dtype=float).reshape(-1, 3)
        self.ranges = np.asarray(ranges, dtype=float).reshape(-1)
        self.kinds = np.asarray(kinds, dtype=np.int8).reshape(-1)

    def __len__(self):
        return len(self.positions)


FACADE, POLE, GROUND, FAR, TUNNEL, WALL, CLUTTER = range(7)
KIND_NAMES = ["facade", "pole", "ground", "far", "tunnel", "wall", "clutter"]


def _tunnel_intervals(path_length, rng, per_km=1.5, min_length=40.0, max_length=120.0):
    count = int(rng.poisson(per_km * path_length / 1000.0))
    intervals = []
    for _ in range(count):
        length = rng.uniform(min_length, max_length)
        start = rng.uniform(0, max(path_length - length, 1.0))
        intervals.append((start, start + length))
    return intervals


class _Chunks:
    def __init__(self):
        self.positions, self.normals, self.ranges, self.kinds = [], [], [], []

    def add(self, positions, normals, ranges, kind):
        self.positions.append(positions)
        self.normals.append(normals)
        self.ranges.append(ranges)
        self.kinds.append(np.full(len(positions), kind, dtype=np.int8))

    def landmarks(self):
        if not self.positions:
            return Landmarks(np.zeros((0, 3)), np.zeros((0, 3)), np.zeros(0), np.zeros(0))
        return Landmarks(np.vstack(self.positions), np.vstack(self.normals),
                         np.concatenate(self.ranges), np.concatenate(self.kinds))


def street(poses, rng, density=1.0, camera_height_m=1.65, step_m=2.0, typical_range_m=35.0):
    """Landmarks along the road the camera drives.

    Walking the path in steps of step_m, each side of the road is a block of facade (a setback of
    5-15 m drawn per block, 15-60 m long) or a gap (a side street: distant points only). Tunnels
    (1.5 per km, 40-120 m) have walls 5 m away, seen over a shorter range, and lights under the ceiling. Poles and trees stand 3-8 m
    from the road; a few points lie on the road. A place already furnished (a revisit) is not
    furnished again, so a loop sees the same landmarks. density scales every count."""
    centres = np.array([p[:3, 3] for p in poses])
    steps = np.linalg.norm(np.diff(centres, axis=0), axis=1)
    arclength = np.concatenate([[0.0], np.cumsum(steps)])
    tunnels = _tunnel_intervals(arclength[-1], rng)
    chunks = _Chunks()
    furnished = {}  # cell -> arclength when first furnished
    cell = 6.0
    block_left = {"remaining": 0.0}
    block_right = {"remaining": 0.0}
    next_s = 0.0
    for k, pose in enumerate(poses):
        if arclength[k] < next_s:
            continue
        next_s = arclength[k] + step_m
        key = tuple(np.floor(centres[k] / cell).astype(int))
        if key in furnished and arclength[k] - furnished[key] > 3 * cell:
            continue  # a revisit: the place has its landmarks
        furnished.setdefault(key, arclength[k])
        rotation = pose[:3, :3]
        up = -rotation[:, 1]
        forward = rotation[:, 2] - np.dot(rotation[:, 2], up) * up
        norm = np.linalg.norm(forward)
        if norm < 1e-6:
            continue
        forward /= norm
        left = np.cross(up, forward)
        ground = centres[k] - camera_height_m * up
        # Tunnels run straight: where the road turns (over 1 deg per metre) it is in the open.
        turn = np.degrees(np.arccos(np.clip(np.dot(pose[:3, 2], poses[min(k + 1, len(poses) - 1)][:3, 2]), -1, 1)))
        straight = turn < 1.0 * max(steps[min(k, len(steps) - 1)], 1e-3)
        in_tunnel = straight and any(a <= arclength[k] <= b for a, b in tunnels)
        for side, block in ((1.0, block_left), (-1.0, block_right)):
            if block["remaining"] <= 0:
                block["facade"] = rng.random() < 0.75
                block["setback"] = rng.uniform(5.0, 15.0)
                block["remaining"] = rng.uniform(15.0, 60.0) if block["facade"] else rng.uniform(5.0, 25.0)
            block["remaining"] -= step_m
            lateral = side * left
            if in_tunnel:
                n = rng.poisson(12.0 * density)
                along = rng.uniform(0, step_m, n)[:, None]
                height = rng.uniform(0.0, 5.0, n)[:, None]
                positions = ground + along * forward + 5.0 * lateral + height * up
                chunks.add(positions, np.tile(-lateral, (n, 1)),
                           typical_range_m * rng.uniform(0.3, 0.8, n), TUNNEL)
                continue
            if block["facade"]:
                n = rng.poisson(28.0 * density)
                along = rng.uniform(0, step_m, n)[:, None]
                setback = block["setback"] + rng.normal(0, 0.3, n)[:, None]
                height = rng.uniform(0.2, 12.0, n)[:, None]
                positions = ground + along * forward + setback * lateral + height * up
                chunks.add(positions, np.tile(-lateral, (n, 1)),
                           typical_range_m * rng.lognormal(0.0, 0.35, n), FACADE)
            else:
                n = rng.poisson(6.0 * density)
                along = rng.uniform(0, step_m, n)[:, None]
                distance = rng.uniform(20.0, 70.0, n)[:, None]
                height = rng.uniform(0.0, 20.0, n)[:, None]
                positions = ground + along * forward + distance * lateral + height * up
                chunks.add(positions, np.zeros((n, 3)),
                           rng.uniform(1.5, 3.0, n) * typical_range_m, FAR)
            n = rng.poisson(3.0 * density)
            along = rng.uniform(0, step_m, n)[:, None]
            offset = rng.uniform(3.0, 8.0, n)[:, None]
            height = rng.uniform(0.3, 6.0, n)[:, None]
            positions = ground + along * forward + offset * lateral + height * up
            chunks.add(positions, np.zeros((n, 3)), typical_range_m * rng.uniform(0.3, 0.9, n), POLE)
        if in_tunnel:  # its lights, in a row under the ceiling
            n = rng.poisson(1.5 * density)
            along = rng.uniform(0, step_m, n)[:, None]
            across = rng.uniform(-3.0, 3.0, n)[:, None]
            positions = ground + along * forward + across * left + 4.5 * up
            chunks.add(positions, np.tile(-up, (n, 1)), typical_range_m * rng.uniform(0.5, 1.2, n), TUNNEL)
        else:
            n = rng.poisson(2.5 * density)
            along = rng.uniform(0, step_m, n)[:, None]
            across = rng.uniform(-4.0, 4.0, n)[:, None]
            positions = ground + along * forward + across * left
            chunks.add(positions, np.tile(up, (n, 1)), typical_range_m * rng.uniform(0.2, 0.5, n), GROUND)
    return chunks.landmarks(), tunnels


def room(poses, rng, density=1.0, margin_m=(1.2, 2.5), typical_range_m=5.0):
    """A furnished room around a hand-held or MAV motion: its six faces 1.2-2.5 m beyond the
    motion's extent, textured in patches (posters, shelves) and bare between, and clutter (desks,
    chairs) inside, kept 0.6 m away from the path so that no camera stands in an object."""
    centres = np.array([p[:3, 3] for p in poses])
    low = centres.min(axis=0) - rng.uniform(*margin_m, 3)
    high = centres.max(axis=0) + rng.uniform(*margin_m, 3)
    size = high - low
    chunks = _Chunks()
    for axis in range(3):
        for face, normal_sign in ((low[axis], 1.0), (high[axis], -1.0)):
            others = [a for a in range(3) if a != axis]
            area = size[others[0]] * size[others[1]]
            # Texture in patches: a face is mostly bare, with 3-8 dense patches.
            for _ in range(int(rng.integers(3, 9))):
                patch_centre = low[others] + rng.uniform(0, 1, 2) * size[others]
                patch_size = rng.uniform(0.3, 1.2, 2) * np.minimum(size[others], 3.0)
                n = rng.poisson(density * 120.0 * patch_size[0] * patch_size[1])
                points = np.zeros((n, 3))
                points[:, axis] = face
                for d, other in enumerate(others):
                    points[:, other] = np.clip(patch_centre[d] + rng.uniform(-0.5, 0.5, n) * patch_size[d],
                                               low[other], high[other])
                normal = np.zeros(3)
                normal[axis] = normal_sign
                chunks.add(points, np.tile(normal, (n, 1)), typical_range_m * rng.lognormal(0, 0.3, n), WALL)
            n = rng.poisson(density * 4.0 * area)
            points = np.zeros((n, 3))
            points[:, axis] = face
            for other in others:
                points[:, other] = rng.uniform(low[other], high[other], n)
            normal = np.zeros(3)
            normal[axis] = normal_sign
            chunks.add(points, np.tile(normal, (n, 1)), typical_range_m * rng.lognormal(0, 0.3, n), WALL)
    n = rng.poisson(density * 15.0 * size.prod() ** (2.0 / 3.0))
    clutter = low + rng.uniform(0, 1, (n, 3)) * size
    clearance = np.min(np.linalg.norm(clutter[:, None, :] - centres[None, ::max(1, len(centres) // 400), :],
                                      axis=2), axis=1)
    clutter = clutter[clearance > 0.6]
    chunks.add(clutter, np.zeros((len(clutter), 3)), typical_range_m * rng.uniform(0.4, 1.0, len(clutter)), CLUTTER)
    return chunks.landmarks(), []
