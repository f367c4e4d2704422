"""ramap: camera poses by motion averaging, COLMAP in and out.

    import ramap
    models = ramap.global_mapping("database.db", "images", "sparse")
    print(models[0].summary())

The calls take the command line's option names, flat or nested:
{"Mapper.refine": 0} or {"Mapper": {"refine": 0}}. A wrong name or value raises ValueError with
the command line's message. Every call releases the GIL while it works, and Ctrl-C stops it
cleanly (KeyboardInterrupt; nothing half-written is left).
"""

import json
import numbers
import os
import warnings

from . import _core
from ._core import Camera, Image, InputError, Point3D, Reconstruction, Rigid3d

__all__ = [
    "Camera",
    "Image",
    "InputError",
    "MappingResult",
    "Point3D",
    "Reconstruction",
    "Rigid3d",
    "evaluate",
    "extract_features",
    "global_mapping",
    "match",
    "mapper_option_defaults",
    "mapper_option_names",
    "reconstruct",
]


class MappingResult(dict):
    """The models of one mapping, {index: Reconstruction}, largest first (as pycolmap's).

    summary: the mapper's summary (stage seconds, dropped images and pairs with their reasons,
             certificates), as summary.json holds it.
    reason:  why nothing was reconstructed, when the dict is empty; "" otherwise.
    """

    def __init__(self, models, summary, reason):
        super().__init__(models)
        self.summary = summary
        self.reason = reason


def _option_text(name, value):
    """A Python value as the command line would spell it."""
    if isinstance(value, bool):
        return "1" if value else "0"
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        return repr(float(value))
    if isinstance(value, (str, os.PathLike)):
        return os.fspath(value)
    if isinstance(value, (list, tuple)):  # a list option: auc_thresholds=[1, 3, 5]
        return ",".join(_option_text(name, item) for item in value)
    raise ValueError(f"--{name}: {value!r} is not a number, a bool, a string or a list of them")


def _flat_options(options):
    """{"Section": {"option": v}} and {"Section.option": v} alike -> {"Section.option": "text"}."""
    flat = {}
    for key, value in (options or {}).items():
        if isinstance(value, dict):
            for inner_key, inner_value in _flat_options(value).items():
                name = f"{key}.{inner_key}"
                flat[name] = inner_value
        else:
            flat[key] = value
    return {name: (v if isinstance(v, str) else _option_text(name, v)) for name, v in flat.items()}


def mapper_option_names():
    """Every mapper option's name ("Mapper.refine", ...), as `ramap mapper -h` lists them."""
    return _core.mapper_option_names()


def mapper_option_defaults():
    """{name: default as text} for every mapper option."""
    return _core.mapper_option_defaults()


def global_mapping(database_path, image_path="", output_path="", options=None, progress=None,
                   log=False):
    """Camera poses and points from a COLMAP database by motion averaging.

    The same call shape as pycolmap.incremental_mapping / global_mapping: the models are written
    to output_path/0, output_path/1, ... (largest first) with output_path/summary.json, as
    `ramap mapper` writes them, and returned as {index: Reconstruction}. An empty output_path
    writes nothing. image_path (optional) gives the points their colours.

    options:  the command line's names, flat or nested (see mapper_option_names()).
    progress: called as progress(stage, seconds, message) when each stage ends.
    log:      print the command line's stage lines.

    Returns a MappingResult (a dict): empty, with .reason, when nothing could be reconstructed.
    """
    models, summary_json, reason = _core.global_mapping(
        os.fspath(database_path), os.fspath(image_path or ""), os.fspath(output_path or ""),
        _flat_options(options), progress, bool(log))
    if reason:
        warnings.warn(f"ramap.global_mapping: {reason}", RuntimeWarning, stacklevel=2)
    return MappingResult(dict(enumerate(models)), json.loads(summary_json), reason)


def reconstruct(image_path, output_path, options=None, image_list="", progress=None, log=False):
    """Images to models in one call, as `ramap reconstruct`: features, matching by the plan the
    options choose, the mapper (with loop closure after sequential matching).

    Writes output_path/database.db (COLMAP reads it too) and output_path/sparse/0, 1, ... with
    summary.json. options: every name `ramap reconstruct -h` lists (ImageReader.*,
    FeatureExtraction.*, Matching.*, the mapper's, LoopClosure.*), flat or nested. Returns a
    MappingResult, as global_mapping does.
    """
    models, summary_json, reason = _core.reconstruct(
        os.fspath(image_path), os.fspath(output_path), _flat_options(options),
        os.fspath(image_list or ""), progress, bool(log))
    if reason:
        warnings.warn(f"ramap.reconstruct: {reason}", RuntimeWarning, stacklevel=2)
    return MappingResult(dict(enumerate(models)), json.loads(summary_json), reason)


def extract_features(image_path, database_path, options=None, image_list="", log=False):
    """Features of the images (SIFT by default, or ORB) into a new COLMAP database, as
    `ramap feature_extractor`. options: ImageReader.*, FeatureExtraction.*, Database.generation.
    Returns the number of images read."""
    return _core.extract_features(os.fspath(image_path), os.fspath(database_path),
                                  _flat_options(options), os.fspath(image_list or ""), bool(log))


def match(database_path, options=None, log=False):
    """Matches and verifies the pairs of a database's images by the plan the options choose, as
    `ramap matcher`. options: Matching.*. Returns the matching summary (plan, pairs, seconds)."""
    return _core.match(os.fspath(database_path), _flat_options(options), bool(log))


def evaluate(model, ground_truth, format, image_list="", database_path="", options=None):
    """Scores a model's poses against a ground truth, as `ramap evaluate` does.

    model: a model folder; format: tum, kitti, strecha, middlebury or colmap. options: the
    command's own names (estimate_scale, robust_alignment, robust_alignment_max_error,
    auc_thresholds, min_baseline, ordered_pairs). Returns the evaluation as `ramap evaluate
    --output_path` writes it (registered images, ATE after Sim(3) alignment, rotation errors,
    relative pose AUC).
    """
    return _core.evaluate(os.fspath(model), os.fspath(ground_truth), format,
                          os.fspath(image_list or ""), os.fspath(database_path or ""),
                          _flat_options(options))
