"""ramap.reconstruct, extract_features and match against the command line on real images
(templeRing from ../shared/data; skipped with a message where the data is absent)."""

import os
import pathlib

import pytest

import ramap
from conftest import run_cli

DATA = pathlib.Path(os.environ.get("RAMAP_DATA_DIR") or os.environ.get("RAMAP_SHARED_DATA_DIR", ""))
TEMPLE = DATA / "middlebury_templeRing"
# One thread everywhere: the runs are then the same to the last bit.
OPTIONS = {"ImageReader": {"camera_model": "PINHOLE",
                           "camera_params": "1520.4,1525.9,302.32,246.87", "single_camera": 1},
           "Mapper.num_threads": 1, "Matching.num_threads": 1, "FeatureExtraction.num_threads": 1}
CLI_OPTIONS = ["--ImageReader.camera_model", "PINHOLE", "--ImageReader.camera_params",
               "1520.4,1525.9,302.32,246.87", "--ImageReader.single_camera", 1,
               "--Mapper.num_threads", 1, "--Matching.num_threads", 1,
               "--FeatureExtraction.num_threads", 1]


@pytest.fixture(scope="module")
def twelve_images(tmp_path_factory):
    if not (TEMPLE / "templeR0001.png").exists():
        pytest.skip(f"templeRing is not in {TEMPLE} (set RAMAP_DATA_DIR)")
    image_list = tmp_path_factory.mktemp("lists") / "twelve.txt"
    image_list.write_text("".join(f"templeR{k:04d}.png\n" for k in range(1, 13)))
    return image_list


def test_reconstruct_equals_the_command_line(twelve_images, tmp_path):
    run_cli("reconstruct", "--image_path", TEMPLE, "--image_list", twelve_images,
            "--output_path", tmp_path / "cli", *CLI_OPTIONS)
    models = ramap.reconstruct(TEMPLE, tmp_path / "python", OPTIONS, image_list=twelve_images)
    assert sum(model.num_reg_images() for model in models.values()) == 12
    for index in models:
        for part in ["cameras.bin", "images.bin", "points3D.bin"]:
            cli = tmp_path / "cli" / "sparse" / str(index) / part
            assert cli.read_bytes() == (tmp_path / "python" / "sparse" / str(index) / part).read_bytes()
    assert models.summary["num_registered_images"] == 12


def test_extract_features_and_match_write_the_commands_database(twelve_images, tmp_path):
    database = tmp_path / "python.db"
    extraction = {"ImageReader": OPTIONS["ImageReader"], "FeatureExtraction.num_threads": 1}
    assert ramap.extract_features(TEMPLE, database, extraction, image_list=twelve_images) == 12
    summary = ramap.match(database, {"Matching.num_threads": 1})
    assert summary["mode"] == "exhaustive" and summary["pairs_verified"] > 11
    models = ramap.global_mapping(database, "", tmp_path / "sparse", {"Mapper.num_threads": 1})
    assert sum(model.num_reg_images() for model in models.values()) == 12
    with pytest.raises(ValueError, match="Matching.mode: 'nearby' is not auto, sequential"):
        ramap.match(database, {"Matching": {"mode": "nearby"}})
    with pytest.raises(ValueError, match="exists"):
        ramap.extract_features(TEMPLE, database, extraction, image_list=twelve_images)
