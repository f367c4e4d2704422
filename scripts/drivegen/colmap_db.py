"""A COLMAP 3.8 database written with sqlite3 alone (the format COLMAP 3.8 documents: float32
keypoint rows of x, y and an affine shape, uint32 match rows, float64 geometry blobs)."""
import sqlite3

import numpy as np

SCHEMA = """
CREATE TABLE cameras (camera_id INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL, model INTEGER NOT NULL,
  width INTEGER NOT NULL, height INTEGER NOT NULL, params BLOB, prior_focal_length INTEGER NOT NULL);
CREATE TABLE images (image_id INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL, name TEXT NOT NULL UNIQUE,
  camera_id INTEGER NOT NULL, prior_qw REAL, prior_qx REAL, prior_qy REAL, prior_qz REAL,
  prior_tx REAL, prior_ty REAL, prior_tz REAL,
  CONSTRAINT image_id_check CHECK(image_id >= 0 and image_id < 2147483647),
  FOREIGN KEY(camera_id) REFERENCES cameras(camera_id));
CREATE UNIQUE INDEX index_name ON images(name);
CREATE TABLE keypoints (image_id INTEGER PRIMARY KEY NOT NULL, rows INTEGER NOT NULL,
  cols INTEGER NOT NULL, data BLOB, FOREIGN KEY(image_id) REFERENCES images(image_id) ON DELETE CASCADE);
CREATE TABLE descriptors (image_id INTEGER PRIMARY KEY NOT NULL, rows INTEGER NOT NULL,
  cols INTEGER NOT NULL, data BLOB, FOREIGN KEY(image_id) REFERENCES images(image_id) ON DELETE CASCADE);
CREATE TABLE matches (pair_id INTEGER PRIMARY KEY NOT NULL, rows INTEGER NOT NULL, cols INTEGER NOT NULL,
  data BLOB);
CREATE TABLE two_view_geometries (pair_id INTEGER PRIMARY KEY NOT NULL, rows INTEGER NOT NULL,
  cols INTEGER NOT NULL, data BLOB, config INTEGER NOT NULL, F BLOB, E BLOB, H BLOB, qvec BLOB, tvec BLOB);
"""

PINHOLE = 1
CALIBRATED = 2
MAX_IMAGE_ID = 2147483647


def pair_id(image_id1, image_id2):
    low, high = min(image_id1, image_id2), max(image_id1, image_id2)
    return low * MAX_IMAGE_ID + high


class Database:
    def __init__(self, path):
        self.connection = sqlite3.connect(path)
        self.connection.executescript(SCHEMA)

    def add_camera(self, camera, prior_focal_length=True):
        params = np.array([camera.fx, camera.fy, camera.cx, camera.cy], dtype=np.float64)
        cursor = self.connection.execute(
            "INSERT INTO cameras (model, width, height, params, prior_focal_length) VALUES (?, ?, ?, ?, ?)",
            (PINHOLE, camera.width, camera.height, params.tobytes(), int(prior_focal_length)))
        return cursor.lastrowid

    def add_image(self, name, camera_id):
        cursor = self.connection.execute("INSERT INTO images (name, camera_id) VALUES (?, ?)", (name, camera_id))
        return cursor.lastrowid

    def add_keypoints(self, image_id, pixels, rng):
        """Rows x, y, a11, a12, a21, a22: an affine shape of random scale and orientation."""
        n = len(pixels)
        scale = rng.uniform(1.5, 6.0, n)
        angle = rng.uniform(-np.pi, np.pi, n)
        rows = np.column_stack([pixels[:, 0], pixels[:, 1], scale * np.cos(angle), -scale * np.sin(angle),
                                scale * np.sin(angle), scale * np.cos(angle)]).astype(np.float32)
        self.connection.execute("INSERT INTO keypoints VALUES (?, ?, ?, ?)", (image_id, n, 6, rows.tobytes()))

    def add_matches(self, image_id1, image_id2, matches):
        matches = self._ordered(image_id1, image_id2, matches)
        self.connection.execute("INSERT INTO matches VALUES (?, ?, ?, ?)",
                                (pair_id(image_id1, image_id2), len(matches), 2, matches.tobytes()))

    def add_two_view_geometry(self, image_id1, image_id2, inliers, essential, fundamental):
        """essential and fundamental map image_id1's points to image_id2's lines (image_id1 < image_id2)."""
        assert image_id1 < image_id2
        inliers = self._ordered(image_id1, image_id2, inliers)
        identity = np.array([1.0, 0.0, 0.0, 0.0])
        self.connection.execute(
            "INSERT INTO two_view_geometries VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
            (pair_id(image_id1, image_id2), len(inliers), 2, inliers.tobytes(), CALIBRATED,
             fundamental.astype(np.float64).tobytes(), essential.astype(np.float64).tobytes(),
             np.eye(3).tobytes(), identity.tobytes(), np.zeros(3).tobytes()))

    @staticmethod
    def _ordered(image_id1, image_id2, matches):
        matches = np.asarray(matches, dtype=np.uint32).reshape(-1, 2)
        return matches if image_id1 < image_id2 else matches[:, ::-1].copy()

    def commit(self):
        self.connection.commit()

    def close(self):
        self.connection.commit()
        self.connection.close()
