"""ramap.Reconstruction: reading, writing BIN and TXT, and the arrays it hands out."""

import gc

import numpy as np
import pytest

import ramap


@pytest.fixture(scope="module")
def model(default_scene, tmp_path_factory):
    output = tmp_path_factory.mktemp("mapped")
    return ramap.global_mapping(default_scene / "database.db", "", output,
                                {"Mapper.refine": 0})[0]


def assert_same_model(a, b, exact=True):
    same = np.array_equal if exact else (lambda x, y: np.allclose(x, y, rtol=0, atol=1e-9))
    assert a.cameras.keys() == b.cameras.keys()
    for camera_id, camera in a.cameras.items():
        other = b.cameras[camera_id]
        assert (camera.model, camera.width, camera.height) == (other.model, other.width,
                                                               other.height)
        assert same(camera.params, other.params)
    assert a.images.keys() == b.images.keys()
    for image_id, image in a.images.items():
        other = b.images[image_id]
        assert image.name == other.name and image.camera_id == other.camera_id
        assert same(image.cam_from_world.matrix(), other.cam_from_world.matrix())
        assert same(image.points2D, other.points2D)
        assert np.array_equal(image.point3D_ids, other.point3D_ids)
    assert a.points3D.keys() == b.points3D.keys()
    assert same(a.points3D_xyz(), b.points3D_xyz())
    for point_id, point in a.points3D.items():
        assert np.array_equal(point.track, b.points3D[point_id].track)


@pytest.mark.parametrize("binary", [True, False])
def test_round_trip(model, tmp_path, binary):
    model.write(str(tmp_path), binary=binary)
    suffix = ".bin" if binary else ".txt"
    assert (tmp_path / ("images" + suffix)).exists()
    # Text keeps 17 significant digits: the same doubles.
    assert_same_model(model, ramap.Reconstruction(str(tmp_path)), exact=True)


def test_arrays_have_the_right_shapes(model):
    assert model.num_reg_images() == len(model.images) > 0
    assert model.points3D_xyz().shape == (model.num_points3D(), 3)
    image = next(iter(model.images.values()))
    assert image.cam_from_world.matrix().shape == (3, 4)
    assert image.cam_from_world.rotation.shape == (4,)
    assert image.cam_from_world.translation.shape == (3,)
    assert image.projection_center().shape == (3,)
    assert image.points2D.shape == (len(image.point3D_ids), 2)
    camera = model.cameras[image.camera_id]
    assert camera.params.shape[0] >= 3
    point = next(iter(model.points3D.values()))
    assert point.xyz.shape == (3,) and point.color.dtype == np.uint8
    assert point.track.shape[1] == 2 and point.track.shape[0] >= 2
    # R t: the projection centre is -R^T t.
    pose = image.cam_from_world.matrix()
    assert np.allclose(image.projection_center(), -pose[:, :3].T @ pose[:, 3])


def test_arrays_outlive_their_model(default_scene, tmp_path):
    models = ramap.global_mapping(default_scene / "database.db", "", tmp_path,
                                  {"Mapper.refine": 0})
    xyz = models[0].points3D_xyz()
    first = next(iter(models[0].images.values()))
    keypoints = first.points2D
    expected_xyz, expected_keypoints = xyz.copy(), keypoints.copy()
    assert xyz.flags.owndata or xyz.base is not None and not isinstance(xyz.base, ramap.Reconstruction)
    del models, first
    gc.collect()
    # Memory reused by new allocations would change freed data under a view.
    ramap.Reconstruction(str(tmp_path / "0")).points3D_xyz()
    assert np.array_equal(xyz, expected_xyz)
    assert np.array_equal(keypoints, expected_keypoints)


def test_summary_and_a_missing_model(model, tmp_path):
    assert f"{model.num_reg_images()} registered images" in model.summary()
    with pytest.raises(ValueError, match=str(tmp_path / "missing")):
        ramap.Reconstruction(str(tmp_path / "missing"))


def test_evaluate_against_the_ground_truth(default_scene, tmp_path):
    ramap.global_mapping(default_scene / "database.db", "", tmp_path, {"Mapper.refine": 0})
    evaluation = ramap.evaluate(tmp_path / "0", default_scene / "ground_truth.txt", "tum",
                                database_path=default_scene / "database.db")
    assert evaluation["num_registered"] == evaluation["num_images"] == 120
    with pytest.raises(ValueError, match="format"):
        ramap.evaluate(tmp_path / "0", default_scene / "ground_truth.txt", "nonsense")
    # The command's own options, by its names, checked as the command line checks them.
    two = ramap.evaluate(tmp_path / "0", default_scene / "ground_truth.txt", "tum",
                         database_path=default_scene / "database.db",
                         options={"auc_thresholds": [2, 7.5], "ordered_pairs": True})
    assert sorted(two["relative"]["auc_by_threshold_deg"], key=float) == ["2", "7.5"]
    with pytest.raises(ValueError, match="--auc_thresholds"):
        ramap.evaluate(tmp_path / "0", default_scene / "ground_truth.txt", "tum",
                       database_path=default_scene / "database.db",
                       options={"auc_thresholds": [-5, 0]})
    with pytest.raises(ValueError, match="--min_baselin"):
        ramap.evaluate(tmp_path / "0", default_scene / "ground_truth.txt", "tum",
                       options={"min_baselin": 1})
