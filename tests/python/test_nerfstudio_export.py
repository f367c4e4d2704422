"""`ramap model_converter --output_type NERFSTUDIO` against nerfstudio's converter's steps
(colmap_to_json with its defaults), re-done here with numpy on the same model's text files."""

import json

import numpy as np

from conftest import run_cli


def rotation_from_quaternion(w, x, y, z):
    return np.array([
        [1 - 2 * y * y - 2 * z * z, 2 * x * y - 2 * w * z, 2 * z * x + 2 * w * y],
        [2 * x * y + 2 * w * z, 1 - 2 * x * x - 2 * z * z, 2 * y * z - 2 * w * x],
        [2 * z * x - 2 * w * y, 2 * y * z + 2 * w * x, 1 - 2 * x * x - 2 * y * y]])


def nerfstudio_camera_to_world(qvec, tvec):
    world_to_camera = np.eye(4)
    world_to_camera[:3, :3] = rotation_from_quaternion(*qvec)
    world_to_camera[:3, 3] = tvec
    c2w = np.linalg.inv(world_to_camera)
    c2w[0:3, 1:3] *= -1
    c2w = c2w[np.array([0, 2, 1, 3]), :]
    c2w[2, :] *= -1
    return c2w


def test_transforms_match_nerfstudios_steps(default_scene, tmp_path):
    run_cli("mapper", "--database_path", default_scene / "database.db",
            "--output_path", tmp_path / "sparse", "--Mapper.refine", 0)
    run_cli("model_converter", "--input_path", tmp_path / "sparse/0",
            "--output_path", tmp_path / "text", "--output_type", "TXT")
    run_cli("model_converter", "--input_path", tmp_path / "sparse/0",
            "--output_path", tmp_path / "ns", "--output_type", "NERFSTUDIO")
    transforms = json.loads((tmp_path / "ns/transforms.json").read_text())

    # images.txt: two lines an image, the second (its points) empty for an image without any.
    lines = [line for line in (tmp_path / "text/images.txt").read_text().splitlines()
             if not line.startswith("#")]
    records = [line.split() for line in lines[::2]]
    records.sort(key=lambda record: int(record[0]))
    assert len(transforms["frames"]) == len(records) > 0
    for frame, record in zip(transforms["frames"], records):
        assert frame["colmap_im_id"] == int(record[0])
        assert frame["file_path"] == "images/" + record[9]
        expected = nerfstudio_camera_to_world([float(v) for v in record[1:5]],
                                              [float(v) for v in record[5:8]])
        assert np.abs(np.array(frame["transform_matrix"]) - expected).max() < 1e-9

    camera = [line.split() for line in (tmp_path / "text/cameras.txt").read_text().splitlines()
              if line and not line.startswith("#")][0]
    assert camera[1] == "PINHOLE"
    width, height, fx, fy, cx, cy = (float(v) for v in camera[2:8])
    assert (transforms["w"], transforms["h"]) == (width, height)
    assert transforms["camera_model"] == "OPENCV"
    assert np.allclose([transforms[k] for k in ("fl_x", "fl_y", "cx", "cy")], [fx, fy, cx, cy],
                       rtol=0, atol=1e-9)
    assert transforms["applied_transform"] == [[1, 0, 0, 0], [0, 0, 1, 0], [0, -1, 0, 0]]
    assert (tmp_path / "ns/sparse_pc.ply").read_bytes().startswith(b"ply\n")
