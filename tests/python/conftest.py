"""Shared fixtures: the bundled default scene and a longer one, made by `ramap synthesize`."""

import os
import pathlib
import subprocess

import pytest

CLI = os.environ.get("RAMAP_CLI_PATH", "ramap")
SOURCE_DIR = pathlib.Path(os.environ.get("RAMAP_SOURCE_DIR",
                                         pathlib.Path(__file__).resolve().parents[2]))


def run_cli(*args, check=True):
    """Runs the ramap command line; returns the finished process (stdout and stderr as text)."""
    return subprocess.run([CLI, *map(str, args)], check=check, capture_output=True, text=True)


def synthesize(output_path, args):
    run_cli("synthesize", "--output_path", output_path, *args)
    return pathlib.Path(output_path)


@pytest.fixture(scope="session")
def default_scene(tmp_path_factory):
    """The scene `scripts/quickstart.sh` maps: data/default_scene.args."""
    lines = (SOURCE_DIR / "data" / "default_scene.args").read_text().splitlines()
    args = [word for line in lines if not line.startswith("#") for word in line.split()]
    return synthesize(tmp_path_factory.mktemp("scenes") / "default", args)


@pytest.fixture(scope="session")
def long_scene(tmp_path_factory):
    """A drive long enough (several seconds of mapping) to interrupt."""
    args = ["--Synthetic.layout", "sequential", "--Synthetic.path", "loop",
            "--Synthetic.num_images", "300", "--Synthetic.num_points", "6000",
            "--Synthetic.pixel_noise", "0.5", "--Synthetic.seed", "3"]
    return synthesize(tmp_path_factory.mktemp("scenes") / "long", args)
