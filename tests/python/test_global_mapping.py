"""ramap.global_mapping against `ramap mapper`, options, failures, the GIL and Ctrl-C."""

import _thread
import json
import threading
import time

import numpy as np
import pytest

import ramap
from conftest import run_cli


def poses(model):
    """{name: 3x4 cam_from_world} of a Reconstruction."""
    return {image.name: image.cam_from_world.matrix() for image in model.images.values()}


def test_same_poses_as_the_command_line_with_one_thread(default_scene, tmp_path):
    database = default_scene / "database.db"
    run_cli("mapper", "--database_path", database, "--output_path", tmp_path / "cli",
            "--Mapper.num_threads", 1, "--log_level", 0)
    models = ramap.global_mapping(database, "", tmp_path / "python", {"Mapper.num_threads": 1})
    assert list(models) == [0]
    from_cli = poses(ramap.Reconstruction(str(tmp_path / "cli" / "0")))
    from_python = poses(models[0])
    assert from_cli.keys() == from_python.keys()
    for name, pose in from_cli.items():
        assert np.array_equal(pose, from_python[name]), name
    for part in ["cameras.bin", "images.bin", "points3D.bin"]:
        assert (tmp_path / "cli" / "0" / part).read_bytes() == \
            (tmp_path / "python" / "0" / part).read_bytes(), part
    summary = json.loads((tmp_path / "python" / "summary.json").read_text())
    assert summary["run"]["options"]["Mapper"]["num_threads"] == 1
    assert summary["run"]["pose_priors"]["std_m"] == [3.0, 3.0, 6.0]


def test_options_flat_and_nested_are_the_same_options(default_scene):
    database = default_scene / "database.db"
    flat = ramap.global_mapping(database, options={"Mapper.refine": 0,
                                                   "Mapper.subset_adjustment": 0,
                                                   "RotationAveraging.max_pcg_iterations": 20})
    nested = ramap.global_mapping(database, options={
        "Mapper": {"refine": False, "subset_adjustment": False},
        "RotationAveraging": {"max_pcg_iterations": 20}})
    assert poses(flat[0]).keys() == poses(nested[0]).keys()
    for name, pose in poses(flat[0]).items():
        assert np.array_equal(pose, poses(nested[0])[name])
    # The option took effect: averaging alone runs no bundle adjustment.
    stages = set(flat.summary["stage_seconds"])
    assert "rotation averaging" in stages
    assert "bundle adjustment" not in stages


def test_former_option_names_still_work(default_scene, tmp_path):
    """Renamed options keep their former names (README, "Renamed"), in Python and on the command
    line, and summary.json states them under the names they have now."""
    database = default_scene / "database.db"
    ramap.global_mapping(database, "", tmp_path / "python",
                         options={"Mapper.refine": 0, "PoseGraph": {"keyframe_interval": 12}})
    options = json.loads((tmp_path / "python" / "summary.json").read_text())["run"]["options"]
    assert options["ViewGraph"]["keyframe_interval"] == 12
    assert "PoseGraph" not in options
    run_cli("mapper", "--database_path", database, "--output_path", tmp_path / "sparse",
            "--Mapper.refine", "0", "--PoseGraph.keyframe_interval", "12")
    summary = json.loads((tmp_path / "sparse" / "summary.json").read_text())
    assert summary["run"]["options"]["ViewGraph"]["keyframe_interval"] == 12


def cli_error(*option_args):
    finished = run_cli("mapper", "--database_path", "unused.db", "--output_path", "unused",
                       *option_args, check=False)
    assert finished.returncode == 2
    return finished.stderr.strip()


@pytest.mark.parametrize("options, cli_args", [
    ({"Mapper.refin": 0}, ["--Mapper.refin", "0"]),
    ({"Mapper.num_threads": 0}, ["--Mapper.num_threads", "0"]),
    ({"RotationAveraging.pruning": "sometimes"}, ["--RotationAveraging.pruning", "sometimes"]),
    ({"RelativePose": {"min_num_inliers": 2.5}}, ["--RelativePose.min_num_inliers", "2.5"]),
    # More than the field holds is refused, never wrapped (2^32 would be 0: "all points").
    ({"Mapper.calibration_num_points": 2**32}, ["--Mapper.calibration_num_points", "4294967296"]),
])
def test_wrong_options_give_the_command_lines_message(default_scene, tmp_path, options, cli_args):
    with pytest.raises(ValueError) as raised:
        ramap.global_mapping(default_scene / "database.db", "", tmp_path / "out", options)
    assert cli_error(*cli_args) == "ramap mapper: error: " + str(raised.value)
    assert not (tmp_path / "out").exists()


def test_nothing_reconstructed_is_an_empty_result_with_its_reason(default_scene, tmp_path):
    with pytest.warns(RuntimeWarning, match="no component"):
        models = ramap.global_mapping(default_scene / "database.db", "", tmp_path / "out",
                                      {"Mapper.min_component_size": 100000})
    assert models == {}
    assert "no component of at least 100000 images" in models.reason
    assert not (tmp_path / "out").exists()


def test_progress_is_called_once_per_stage(default_scene):
    stages = []
    ramap.global_mapping(default_scene / "database.db", options={"Mapper.refine": 0},
                         progress=lambda stage, seconds, message: stages.append(stage))
    assert stages[:2] == ["view-graph calibration", "bearings"]
    assert "translation averaging" in stages and "triangulation" in stages


def test_the_gil_is_released_while_mapping(default_scene):
    ticks = []
    done = threading.Event()

    def count():
        while not done.is_set():
            ticks.append(time.monotonic())
            time.sleep(0.002)

    counter = threading.Thread(target=count)
    counter.start()
    start = time.monotonic()
    try:
        ramap.global_mapping(default_scene / "database.db")
    finally:
        done.set()
        counter.join()
    end = time.monotonic()
    during = [t for t in ticks if start < t < end]
    # Held, the GIL would let the counter run at most once per switch interval of the stage
    # callbacks; released, it ticks every few milliseconds throughout.
    assert end - start > 0.5
    assert len(during) > 0.25 * (end - start) / 0.002


def test_ctrl_c_stops_a_long_run_and_leaves_nothing(long_scene, tmp_path):
    output = tmp_path / "out"
    timer = threading.Timer(1.0, _thread.interrupt_main)
    start = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        ramap.global_mapping(long_scene / "database.db", "", output)
    stopped_after = time.monotonic() - start
    timer.join()
    # The run takes about 18 s on 2 cores; it stops at its next step.  
    assert stopped_after < 5.0
    assert not output.exists()
    assert list(tmp_path.iterdir()) == []


def test_in_place_of_pycolmap_incremental_mapping_as_hloc_calls_it(default_scene, tmp_path):
    """docs/python.md's hloc snippet, and then what hloc's run_reconstruction does with the result."""
    incremental_mapping = (
        lambda database_path, image_path, output_path, *options, **named: ramap.global_mapping(
            database_path, image_path, output_path))
    models_path = tmp_path / "models"
    models_path.mkdir()
    pycolmap_options = object()  # hloc passes pycolmap's options, positionally or by name
    reconstructions = incremental_mapping(default_scene / "database.db", "",
                                          models_path, pycolmap_options)
    assert incremental_mapping(default_scene / "database.db", "",
                               tmp_path / "again", options=pycolmap_options)
    largest = max(reconstructions, key=lambda index: reconstructions[index].num_reg_images())
    for filename in ["images.bin", "cameras.bin", "points3D.bin"]:
        (models_path / str(largest) / filename).rename(tmp_path / filename)
    moved = ramap.Reconstruction(str(tmp_path))
    assert moved.num_reg_images() == reconstructions[largest].num_reg_images() == 120
    assert "registered images" in reconstructions[largest].summary()


def test_outputs_are_checked_before_any_work(default_scene, tmp_path):
    images = tmp_path / "images"
    images.mkdir()
    (images / "photo.jpg").write_bytes(b"a user's photo")
    with pytest.raises(ValueError, match="--output_path"):
        ramap.global_mapping(default_scene / "database.db", images, images)
    assert [p.name for p in images.iterdir()] == ["photo.jpg"]


def test_boolean_words_as_the_command_line_took_them(default_scene):
    for word in ["False", "off", "NO", 0, False]:
        ramap._core.check_mapper_options({"Mapper.refine": ramap._flat_options({"v": word})["v"]})
    with pytest.raises(ValueError, match="'maybe' is not 1 or 0"):
        ramap._core.check_mapper_options({"Mapper.refine": "maybe"})
