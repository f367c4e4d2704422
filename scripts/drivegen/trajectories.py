"""Ground-truth motions as camera-to-world poses (x right, y down, z forward)."""
import numpy as np

# EuRoC's cam0 in the body (IMU) frame, from the dataset's sensor.yaml (T_BS of cam0), rounded.
EUROC_BODY_FROM_CAM0 = np.array([
    [0.0149, -0.9999, 0.0041, -0.0216],
    [0.9997, 0.0150, 0.0257, -0.0647],
    [-0.0258, 0.0038, 0.9997, 0.0098],
    [0.0, 0.0, 0.0, 1.0]])


def quaternion_to_matrix(qx, qy, qz, qw):
    q = np.array([qw, qx, qy, qz], dtype=float)
    w, x, y, z = q / np.linalg.norm(q)
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def matrix_to_quaternion(r):
    """(qw, qx, qy, qz) of a rotation matrix, qw >= 0."""
    trace = np.trace(r)
    if trace > 0:
        s = 2.0 * np.sqrt(trace + 1.0)
        q = np.array([0.25 * s, (r[2, 1] - r[1, 2]) / s, (r[0, 2] - r[2, 0]) / s, (r[1, 0] - r[0, 1]) / s])
    else:
        i = int(np.argmax(np.diag(r)))
        j, k = (i + 1) % 3, (i + 2) % 3
        s = 2.0 * np.sqrt(1.0 + r[i, i] - r[j, j] - r[k, k])
        q = np.zeros(4)
        q[0] = (r[k, j] - r[j, k]) / s
        q[1 + i] = 0.25 * s
        q[1 + j] = (r[j, i] + r[i, j]) / s
        q[1 + k] = (r[k, i] + r[i, k]) / s
    q /= np.linalg.norm(q)
    return q if q[0] >= 0 else -q


def _pose(rotation, position):
    pose = np.eye(4)
    pose[:3, :3] = rotation
    pose[:3, 3] = position
    return pose


def _numeric_rows(path, separator=None):
    rows = []
    with open(path) as stream:
        for line in stream:
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            rows.append([float(v) for v in line.split(separator)])
    if not rows:
        raise ValueError(f"{path}: no poses")
    return np.array(rows)


def load_kitti(path):
    rows = _numeric_rows(path)
    if rows.shape[1] != 12:
        raise ValueError(f"{path}: a KITTI pose line has 12 values, found {rows.shape[1]}")
    return [np.vstack([row.reshape(3, 4), [0, 0, 0, 1]]) for row in rows]


def load_tum(path, body_from_camera=None):
    rows = _numeric_rows(path)
    if rows.shape[1] != 8:
        raise ValueError(f"{path}: a TUM pose line has 8 values, found {rows.shape[1]}")
    poses = [_pose(quaternion_to_matrix(*row[4:8]), row[1:4]) for row in rows]
    return [p @ body_from_camera for p in poses] if body_from_camera is not None else poses


def load_euroc_csv(path):
    rows = _numeric_rows(path, ",")
    if rows.shape[1] < 8:
        raise ValueError(f"{path}: a EuRoC ground-truth row has at least 8 values")
    poses = [_pose(quaternion_to_matrix(row[5], row[6], row[7], row[4]), row[1:4]) for row in rows]
    return [p @ EUROC_BODY_FROM_CAM0 for p in poses]


def load(path, kind):
    """kind: kitti, tum (optical centre), euroc_tum (body pose, TUM format), euroc_csv."""
    if kind == "kitti":
        return load_kitti(path)
    if kind == "tum":
        return load_tum(path)
    if kind == "euroc_tum":
        return load_tum(path, EUROC_BODY_FROM_CAM0)
    if kind == "euroc_csv":
        return load_euroc_csv(path)
    raise ValueError(f"unknown trajectory kind '{kind}'")


def guess_kind(path):
    name = path.lower()
    if name.endswith(".csv"):
        return "euroc_csv"
    if "euroc" in name or "v1_0" in name:
        return "euroc_tum"
    if "tum" in name or "freiburg" in name:
        return "tum"
    return "kitti"


def _interpolate_rotation(r0, r1, w):
    q0, q1 = matrix_to_quaternion(r0), matrix_to_quaternion(r1)
    if np.dot(q0, q1) < 0:
        q1 = -q1
    q = (1 - w) * q0 + w * q1  # nlerp: poses are close, the difference to slerp is negligible
    q /= np.linalg.norm(q)
    return quaternion_to_matrix(q[1], q[2], q[3], q[0])


def insert_stops(poses, rng, stops_per_1000=2.0, min_frames=8, max_frames=30):
    """Re-time the motion: the vehicle halts at random places and makes the time up elsewhere.

    The number of frames and the path are kept; at a stop consecutive frames share one pose (no
    baseline at all), and away from the stops each frame moves further than it did.
    Returns (poses, list of (first frame, length) of each stop)."""
    n = len(poses)
    num_stops = int(rng.poisson(stops_per_1000 * n / 1000.0))
    speed = np.ones(n - 1)
    stops = []
    for _ in range(num_stops):
        length = int(rng.integers(min_frames, max_frames + 1))
        if n - 1 <= length + 20:
            break
        first = int(rng.integers(10, n - 1 - length - 10))
        speed[first:first + length] = 0.0
        stops.append((first, length))
    if speed.sum() == 0:
        return list(poses), []
    speed *= (n - 1) / speed.sum()
    parameter = np.concatenate([[0.0], np.cumsum(speed)])
    parameter = np.clip(parameter, 0, n - 1)
    out = []
    for u in parameter:
        k = min(int(np.floor(u)), n - 2)
        w = u - k
        position = (1 - w) * poses[k][:3, 3] + w * poses[k + 1][:3, 3]
        out.append(_pose(_interpolate_rotation(poses[k][:3, :3], poses[k + 1][:3, :3], w), position))
    return out, sorted(stops)
