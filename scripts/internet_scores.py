#!/usr/bin/env python3
"""Scores one mapper's output on an internet conditions set (scripts/make_internet_sets.py).

    internet_scores.py SET_DIR SPARSE_DIR RAMAP_BINARY

SPARSE_DIR holds the models (0/, 1/, ...; .bin or .txt). The scene's model is the one with the
most scene images. Prints one JSON object:
  scene_registered / scene_images: scene images in the scene's model, of all
  distractors_in_scene / distractors: distractors inside the scene's model, of all
  distractors_registered: distractors in any model (their own component is fine)
  focal_error_median / focal_error_max: |f / f_true - 1| over the scene's registered images (each
    image's camera; the mean of fx and fy for a two-focal model)
  auc3: relative pose AUC at 3 degrees over the scene images (unregistered ones count as failures),
    by `ramap evaluate` against the set's ground truth; null where the set has no poses
  num_models: models written
"""

import json
import pathlib
import statistics
import subprocess
import sys
import tempfile


def read_text_model(folder):
    cameras = {}
    for line in (folder / "cameras.txt").read_text().split("\n"):
        if not line.strip() or line.startswith("#"):
            continue
        parts = line.split()
        params = list(map(float, parts[4:]))
        two_focal = parts[1] in ("PINHOLE", "OPENCV", "OPENCV_FISHEYE", "FULL_OPENCV", "FOV",
                                 "THIN_PRISM_FISHEYE")
        cameras[parts[0]] = (params[0] + params[1]) / 2 if two_focal else params[0]
    images = {}
    lines = [line for line in (folder / "images.txt").read_text().split("\n")
             if not line.startswith("#")]
    for line in lines[0::2]:
        parts = line.split()
        if len(parts) >= 10:
            images[parts[9]] = cameras[parts[8]]
    return images


def as_text(model, ramap, scratch):
    if (model / "images.txt").exists():
        return model
    out = scratch / model.name
    out.mkdir()
    subprocess.run([ramap, "model_converter", "--input_path", str(model), "--output_path",
                    str(out), "--output_type", "TXT"], check=True, capture_output=True)
    return out


def main():
    set_dir, sparse, ramap = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2]), sys.argv[3]
    scene = set(set_dir.joinpath("scene_images.txt").read_text().split())
    distractors = set(set_dir.joinpath("distractors.txt").read_text().split())
    true_fx = {}
    for line in set_dir.joinpath("truth.tsv").read_text().split("\n")[1:]:
        parts = line.split("\t")
        if len(parts) >= 4:
            true_fx[parts[0]] = float(parts[3])
    models = sorted(p for p in sparse.iterdir() if p.is_dir() and
                    ((p / "images.bin").exists() or (p / "images.txt").exists()))
    result = {"scene_images": len(scene), "distractors": len(distractors),
              "num_models": len(models), "scene_registered": 0, "distractors_in_scene": 0,
              "distractors_registered": 0, "focal_error_median": None, "focal_error_max": None,
              "auc3": None}
    with tempfile.TemporaryDirectory() as scratch_name:
        scratch = pathlib.Path(scratch_name)
        read = [(model, read_text_model(as_text(model, ramap, scratch))) for model in models]
        for _, images in read:
            result["distractors_registered"] += len(distractors & images.keys())
        if not read:
            print(json.dumps(result))
            return
        best_model, best = max(read, key=lambda entry: len(scene & entry[1].keys()))
        result["scene_registered"] = len(scene & best.keys())
        result["distractors_in_scene"] = len(distractors & best.keys())
        errors = [abs(best[name] / true_fx[name] - 1) for name in scene & best.keys()]
        if errors:
            result["focal_error_median"] = statistics.median(errors)
            result["focal_error_max"] = max(errors)
        ground_truth = set_dir / "ground_truth"
        if ground_truth.joinpath("images.txt").read_text().strip():
            # The scene images with a pose: all of them where the set has poses.
            evaluation = scratch / "evaluation.json"
            subprocess.run([ramap, "evaluate", "--model_path", str(best_model), "--ground_truth",
                            str(ground_truth), "--ground_truth_format", "colmap", "--image_list",
                            str(set_dir / "scene_images.txt"), "--output_path", str(evaluation)],
                           check=True, capture_output=True)
            scores = json.loads(evaluation.read_text())
            result["auc3"] = 100 * scores["relative"]["auc_by_threshold_deg"]["3"]
            result["rotation_error_median_deg"] = scores["rotation_error_deg"]["median"]
    print(json.dumps(result))


if __name__ == "__main__":
    main()
