#!/usr/bin/env python3
"""Gives every camera of a COLMAP database the known model and parameters and drops its two-view
geometries, which were verified with the old camera (scripts/prepare_datasets.sh).

    set_camera.py DATABASE MODEL PARAMS      (PARAMS comma-separated, at full resolution)
"""
import sqlite3
import struct
import sys

# COLMAP's camera model ids (colmap/sensor/models.h).
MODEL_IDS = {"SIMPLE_PINHOLE": (0, 3), "PINHOLE": (1, 4), "SIMPLE_RADIAL": (2, 4), "RADIAL": (3, 5),
             "OPENCV": (4, 8)}


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    database, model, params_text = sys.argv[1:]
    if model not in MODEL_IDS:
        sys.exit(f"set_camera.py: camera model {model} not one of {', '.join(MODEL_IDS)}")
    model_id, num_params = MODEL_IDS[model]
    params = [float(value) for value in params_text.split(",")]
    if len(params) != num_params:
        sys.exit(f"set_camera.py: {model} takes {num_params} parameters, got {len(params)}")
    connection = sqlite3.connect(database)
    with connection:
        connection.execute("UPDATE cameras SET model = ?, params = ?, prior_focal_length = 1",
                           (model_id, struct.pack(f"<{num_params}d", *params)))
        connection.execute("DELETE FROM two_view_geometries")
    connection.close()


if __name__ == "__main__":
    main()
