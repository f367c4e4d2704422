#!/usr/bin/env python3
"""Builds "internet conditions" benchmark sets from the real sets of ../shared/data.

An internet photo collection breaks what curated captures keep: every photo is cropped and resized
differently (so one focal length and principal point per image), EXIF is kept after the crop (now
wrong), stripped of the original pixel size, or wrong outright (a few percent to 10x), most cameras
have one image, there are near-duplicates, and some photos show something else. This script makes
such sets from images whose ground truth is exact, and carries the ground truth through every crop
and resize, so the truth stays exact: one PINHOLE camera per image.

    make_internet_sets.py DATA_DIR OUT_DIR [--seed N] [--sets NAME,...]

Each set OUT_DIR/NAME holds:
  images/            JPEGs named img_XXXXXX.jpg in a random order (no frame numbers to exploit)
  ground_truth/      a COLMAP text model (cameras.txt, images.txt, empty points3D.txt) of the
                     scene's images: their poses and each image's own intrinsics. Distractors and
                     (for sceaux_castle, which has no poses) the scene's poses are absent.
  scene_images.txt   the scene's image names (the input images evaluation scores)
  distractors.txt    the distractors' names: photos of another set, which verify among themselves
  truth.tsv          per image: name, role (scene, duplicate, distractor), source image, true fx,
                     what was written into EXIF and the focal length that EXIF implies when read
                     right (0: none)
  SOURCE.txt         how it was made

Needs python3-opencv, python3-numpy and the exiv2 command (Debian packages).
"""

import argparse
import math
import pathlib
import random
import subprocess
import sys

import cv2
import numpy as np

# A sensor width for the EXIF focal plane tags (an APS-C camera's); any value gives the same focal
# length in pixels when read right.
SENSOR_WIDTH_MM = 23.5


class Source:
    """One image of a real set: its file, intrinsics (fx, fy, cx, cy) and pose (R, t: world to
    camera), or no pose."""

    def __init__(self, path, K, R=None, t=None):
        self.path = path
        self.K = K
        self.R = R
        self.t = t


def read_strecha(folder):
    sources = []
    for camera in sorted((folder / "gt_dense_cameras").glob("*.camera")):
        rows = [list(map(float, line.split())) for line in camera.read_text().split("\n")
                if line.strip()]
        K = np.array(rows[0:3])
        R_c2w = np.array(rows[4:7])
        centre = np.array(rows[7])
        R = R_c2w.T
        sources.append(Source(folder / "images" / camera.name[:-len(".camera")],
                              K, R, -R @ centre))
    return sources


def read_middlebury(folder):
    sources = []
    lines = (folder / "templeR_par.txt").read_text().split("\n")[1:]
    for line in lines:
        parts = line.split()
        if len(parts) != 22:
            continue
        values = list(map(float, parts[1:]))
        sources.append(Source(folder / parts[0], np.array(values[0:9]).reshape(3, 3),
                              np.array(values[9:18]).reshape(3, 3), np.array(values[18:21])))
    return sources


def read_kitti(folder, step):
    K = np.array([[707.0912, 0, 601.8873], [0, 707.0912, 183.1104], [0, 0, 1]])
    sources = []
    for index, line in enumerate((folder / "poses_gt.txt").read_text().split("\n")):
        if not line.strip() or index % step:
            continue
        pose = np.array(list(map(float, line.split()))).reshape(3, 4)
        R = pose[:, :3].T
        sources.append(Source(folder / "image_0" / f"{index:06d}.png", K, R, -R @ pose[:, 3]))
    return sources


def quaternion_to_matrix(w, x, y, z):
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def matrix_to_quaternion(R):
    w = math.sqrt(max(0.0, 1 + R[0, 0] + R[1, 1] + R[2, 2])) / 2
    x = math.sqrt(max(0.0, 1 + R[0, 0] - R[1, 1] - R[2, 2])) / 2
    y = math.sqrt(max(0.0, 1 - R[0, 0] + R[1, 1] - R[2, 2])) / 2
    z = math.sqrt(max(0.0, 1 - R[0, 0] - R[1, 1] + R[2, 2])) / 2
    x = math.copysign(x, R[2, 1] - R[1, 2])
    y = math.copysign(y, R[0, 2] - R[2, 0])
    z = math.copysign(z, R[1, 0] - R[0, 1])
    return w, x, y, z


def read_colmap_text(folder, image_folder):
    """A COLMAP text model's images (the reference of lund_door: not exact, a model)."""
    cameras = {}
    for line in (folder / "cameras.txt").read_text().split("\n"):
        if line.startswith("#") or not line.strip():
            continue
        parts = line.split()
        params = list(map(float, parts[4:]))
        f, cx, cy = (params[0], params[1], params[2]) if parts[1].startswith("SIMPLE") else \
            (params[0], params[2], params[3])
        cameras[parts[0]] = np.array([[f, 0, cx], [0, f, cy], [0, 0, 1]])
    sources = []
    lines = [line for line in (folder / "images.txt").read_text().split("\n")
             if not line.startswith("#")]
    for line in lines[0::2]:
        parts = line.split()
        if len(parts) < 10:
            continue
        R = quaternion_to_matrix(*map(float, parts[1:5]))
        sources.append(Source(image_folder / parts[9], cameras[parts[8]], R,
                              np.array(list(map(float, parts[5:8])))))
    return sources


def read_sceaux(folder):
    K = np.loadtxt(folder / "images" / "K.txt")
    return [Source(path, K) for path in sorted((folder / "images").glob("*.JPG"))]


def read_base_sets(data):
    return {
        "fountain-P11": (read_strecha(data / "strecha/fountain-P11"), (0.2, 0.4)),
        "Herz-Jesus-P8": (read_strecha(data / "strecha/Herz-Jesus-P8"), (0.2, 0.4)),
        "templeRing": (read_middlebury(data / "middlebury_templeRing"), (0.75, 1.0)),
        "kitti07_first160": (read_kitti(data / "kitti_3dv_tutorial/kitti07_first160", 2),
                             (0.6, 1.0)),
        "lund_door": (read_colmap_text(data / "lund_door/colmap_ground_truth",
                                       data / "lund_door/images"), (0.3, 0.6)),
        "sceaux_castle": (read_sceaux(data / "sceaux_castle"), (0.2, 0.4)),
    }


# The sets: scene, the set its distractors come from, how many, and how many near-duplicates.
SETS = {
    "internet_fountain": ("fountain-P11", "Herz-Jesus-P8", 4, 2),
    "internet_herzjesus": ("Herz-Jesus-P8", "fountain-P11", 4, 2),
    "internet_temple": ("templeRing", "sceaux_castle", 4, 3),
    "internet_kitti": ("kitti07_first160", "lund_door", 4, 3),
    "internet_lund_door": ("lund_door", "templeRing", 5, 2),
    "internet_sceaux": ("sceaux_castle", "fountain-P11", 4, 2),
}


def crop_and_resize(image, K, rng, scale_range):
    """A random crop (each side kept at 65-100%, anywhere) with probability 0.7, then a resize.
    Returns the new image and its exact intrinsics."""
    height, width = image.shape[:2]
    x0 = y0 = 0
    w, h = width, height
    if rng.random() < 0.7:
        w = int(width * rng.uniform(0.65, 1.0))
        h = int(height * rng.uniform(0.65, 1.0))
        x0 = rng.randint(0, width - w)
        y0 = rng.randint(0, height - h)
    scale = rng.uniform(*scale_range)
    new_w, new_h = max(64, round(w * scale)), max(64, round(h * scale))
    crop = image[y0:y0 + h, x0:x0 + w]
    resized = cv2.resize(crop, (new_w, new_h), interpolation=cv2.INTER_AREA
                         if scale < 1 else cv2.INTER_LINEAR)
    sx, sy = new_w / w, new_h / h
    K_new = np.array([[K[0, 0] * sx, 0, (K[0, 2] - x0) * sx],
                      [0, K[1, 1] * sy, (K[1, 2] - y0) * sy], [0, 0, 1]])
    return resized, K_new


def exif_tags(K_original, original_size, rng):
    """EXIF as internet photos carry it, and the focal length (px of the original) that it states
    and the factor it is off by. Kinds: the camera's own tags (focal plane, with the original
    pixel size), the same with the pixel size stripped by an editor, a 35 mm equivalent, a wrong
    35 mm equivalent (a few percent to 10x), none."""
    width, height = original_size
    fx = K_original[0, 0]
    pixels_per_mm = width / SENSOR_WIDTH_MM
    u = rng.random()
    if u < 0.35:
        kind = "focal plane"
    elif u < 0.5:
        kind = "focal plane, pixel size stripped"
    elif u < 0.7:
        kind = "35 mm equivalent"
    elif u < 0.85:
        kind = "35 mm equivalent, wrong"
    else:
        return "none", [], 0.0
    tags = []
    stated = fx
    if kind.startswith("focal plane"):
        f_mm = fx / pixels_per_mm
        tags += [f"set Exif.Photo.FocalLength Rational {round(f_mm * 1000)}/1000",
                 f"set Exif.Photo.FocalPlaneXResolution Rational {round(pixels_per_mm * 1000)}/1000",
                 "set Exif.Photo.FocalPlaneResolutionUnit Short 4"]
    else:
        off = 1.0
        if kind.endswith("wrong"):
            # log-uniform over 1/10..10, at least 5% off
            while abs(math.log(off)) < math.log(1.05):
                off = math.exp(rng.uniform(-math.log(10), math.log(10)))
        f35 = max(1, round(fx / max(width, height) * 36 * off))
        stated = f35 / 36 * max(width, height)
        tags.append(f"set Exif.Photo.FocalLengthIn35mmFilm Short {f35}")
    if kind != "focal plane, pixel size stripped":
        tags += [f"set Exif.Photo.PixelXDimension Long {width}",
                 f"set Exif.Photo.PixelYDimension Long {height}"]
    tags.append("set Exif.Image.Make Ascii ramap-internet-set")
    return kind, tags, stated


def write_image(path, image, tags, quality):
    cv2.imwrite(str(path), image, [cv2.IMWRITE_JPEG_QUALITY, quality])
    if tags:
        command = ["exiv2", "-q"]
        for tag in tags:
            command += ["-M", tag]
        subprocess.run(command + [str(path)], check=True)


def make_set(name, scene, distractor_set, num_distractors, num_duplicates, bases, out, seed):
    rng = random.Random(f"{seed}:{name}")
    folder = out / name
    (folder / "images").mkdir(parents=True, exist_ok=True)
    (folder / "ground_truth").mkdir(exist_ok=True)
    scene_sources, scene_scale = bases[scene]
    distractor_sources, distractor_scale = bases[distractor_set]
    # Distractors: consecutive images of the other set, so that they verify among themselves.
    start = rng.randint(0, len(distractor_sources) - num_distractors)
    entries = [(source, "scene", scene_scale) for source in scene_sources]
    entries += [(source, "duplicate", scene_scale)
                for source in rng.sample(scene_sources, num_duplicates)]
    entries += [(source, "distractor", distractor_scale)
                for source in distractor_sources[start:start + num_distractors]]
    rng.shuffle(entries)
    used = set()
    rows, cameras, images, scene_names, distractors = [], [], [], [], []
    for source, role, scale_range in entries:
        while True:
            image_name = f"img_{rng.randrange(16 ** 6):06x}.jpg"
            if image_name not in used:
                used.add(image_name)
                break
        original = cv2.imread(str(source.path), cv2.IMREAD_COLOR)
        if original is None:
            sys.exit(f"make_internet_sets: cannot read {source.path}")
        height, width = original.shape[:2]
        image, K = crop_and_resize(original, source.K, rng, scale_range)
        kind, tags, stated = exif_tags(source.K, (width, height), rng)
        # The focal length EXIF implies for this file when read right: scaled by the resize
        # where the original pixel size is there, unscaled where it is not.
        implied = 0.0
        if stated > 0:
            resize = image.shape[1] / width if "stripped" not in kind else 1.0
            implied = stated * resize
        write_image(folder / "images" / image_name, image, tags,
                    quality=70 if role == "duplicate" else 90)
        rows.append(f"{image_name}\t{role}\t{source.path.name}\t{K[0, 0]:.3f}\t{kind}\t"
                    f"{implied:.3f}")
        if role == "distractor":
            distractors.append(image_name)
            continue
        scene_names.append(image_name)
        if source.R is None:
            continue
        camera_id = len(cameras) + 1
        cameras.append(f"{camera_id} PINHOLE {image.shape[1]} {image.shape[0]} "
                       f"{K[0, 0]:.6f} {K[1, 1]:.6f} {K[0, 2]:.6f} {K[1, 2]:.6f}")
        w, x, y, z = matrix_to_quaternion(source.R)
        t = source.t
        images.append(f"{camera_id} {w:.12f} {x:.12f} {y:.12f} {z:.12f} {t[0]:.12f} {t[1]:.12f} "
                      f"{t[2]:.12f} {camera_id} {image_name}\n\n")
    (folder / "ground_truth" / "cameras.txt").write_text("\n".join(cameras) + "\n")
    (folder / "ground_truth" / "images.txt").write_text("".join(images))
    (folder / "ground_truth" / "points3D.txt").write_text("")
    (folder / "scene_images.txt").write_text("\n".join(sorted(scene_names)) + "\n")
    (folder / "distractors.txt").write_text("\n".join(sorted(distractors)) + "\n")
    (folder / "truth.tsv").write_text(
        "name\trole\tsource\ttrue_fx\texif\texif_focal_read_right\n" + "\n".join(rows) + "\n")
    (folder / "SOURCE.txt").write_text(
        f"Made by scripts/make_internet_sets.py (seed {seed}) from ../shared/data: the images of "
        f"{scene} (each cropped and resized its own way, {num_duplicates} near-duplicates) and "
        f"{num_distractors} of {distractor_set} as distractors. Ground truth: "
        + ("none for poses (focal lengths only, in truth.tsv)" if not images else
           "the set's own, carried through each crop and resize" +
           (" (lund_door's is a reference COLMAP model, not exact)" if scene == "lund_door"
            else "")) + ". Licences: those of the source sets (their SOURCE.txt).\n")
    print(f"{name}: {len(scene_names)} scene images ({num_duplicates} near-duplicates), "
          f"{len(distractors)} distractors -> {folder}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("data_dir", type=pathlib.Path)
    parser.add_argument("out_dir", type=pathlib.Path)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--sets", default=",".join(SETS))
    args = parser.parse_args()
    bases = read_base_sets(args.data_dir)
    for name in args.sets.split(","):
        if name not in SETS:
            sys.exit(f"make_internet_sets: --sets: unknown set {name} (known: {', '.join(SETS)})")
        make_set(name, *SETS[name], bases, args.out_dir, args.seed)


if __name__ == "__main__":
    main()
