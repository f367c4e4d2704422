#!/usr/bin/env python3
"""How many of the pairs that exhaustive matching verifies ramap's own matching plan found.

    matching_recall.py DATABASE RAMAP_BINARY [SCENE_IMAGES_TXT]

DATABASE is a COLMAP database that `ramap reconstruct` matched without --ImageReader.camera_params:
its verified pairs are the plan's. A copy of it, its matches removed, is matched again with every
pair tried (`--Matching.mode exhaustive --Matching.preemptive_num_features 0`), on the same
features and verified as reconstruct verified them: with F wherever a focal length came from EXIF
(the copy's cameras lose their prior_focal_length flag, which would make `ramap matcher` verify
with E through it). Prints one JSON object:
  images, pairs_tried_exhaustive: images, and the pairs exhaustive matching tries
  verified_exhaustive / verified_plan: pairs verified by each
  recall: verified_plan & verified_exhaustive over verified_exhaustive
  recall_strong: the same over the pairs exhaustive matching verifies with 100 or more inliers
  recall_scene: the same over pairs of two images listed in SCENE_IMAGES_TXT (a set of
    scripts/make_internet_sets.py), when given
"""

import json
import pathlib
import shutil
import sqlite3
import subprocess
import sys
import tempfile

STRONG_INLIERS = 100
MAX_IMAGE_ID = 2147483647  # COLMAP's pair_id = id1 * MAX_IMAGE_ID + id2


def verified_pairs(database):
    """{(id1, id2): inliers} of the pairs with a verified geometry."""
    with sqlite3.connect(database) as db:
        rows = db.execute("SELECT pair_id, rows FROM two_view_geometries WHERE rows > 0").fetchall()
    return {(pair_id // MAX_IMAGE_ID, pair_id % MAX_IMAGE_ID): inliers for pair_id, inliers in rows}


def image_names(database):
    with sqlite3.connect(database) as db:
        return dict(db.execute("SELECT image_id, name FROM images").fetchall())


def recall(found, wanted):
    return None if not wanted else len(found & wanted) / len(wanted)


def exhaustive_pairs(ramap, database):
    """The verified pairs of a copy of `database` matched with every pair tried."""
    with tempfile.TemporaryDirectory() as work:
        exhaustive_db = pathlib.Path(work) / "exhaustive.db"
        shutil.copyfile(database, exhaustive_db)
        with sqlite3.connect(exhaustive_db) as db:
            db.execute("DELETE FROM matches")
            db.execute("DELETE FROM two_view_geometries")
            # ramap's own table of each matched pair's confidence goes with its matches.
            tables = {row[0] for row in db.execute("SELECT name FROM sqlite_master")}
            if "ramap_match_confidence" in tables:
                db.execute("DELETE FROM ramap_match_confidence")
            db.execute("UPDATE cameras SET prior_focal_length = 0")
        command = [ramap, "matcher", "--database_path", str(exhaustive_db), "--log_level", "0",
                   "--Matching.mode", "exhaustive", "--Matching.preemptive_num_features", "0"]
        run = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        if run.returncode != 0:
            sys.exit(f"matching_recall: {ramap} matcher failed on a copy of {database}: "
                     f"{run.stderr.strip()}")
        return verified_pairs(exhaustive_db)


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    database, ramap = pathlib.Path(sys.argv[1]), sys.argv[2]
    if not database.is_file():
        sys.exit(f"matching_recall: no database at {database}")
    if shutil.which(ramap) is None:
        sys.exit(f"matching_recall: no ramap binary at {ramap}")
    try:
        plan = verified_pairs(database)
        names = image_names(database)
    except sqlite3.DatabaseError as error:
        sys.exit(f"matching_recall: {database} is not a COLMAP database ({error})")
    if not plan:
        sys.exit(f"matching_recall: {database} holds no verified pair: match it first")
    exhaustive = exhaustive_pairs(ramap, database)
    found = set(plan)
    scores = {
        "images": len(names),
        "pairs_tried_exhaustive": len(names) * (len(names) - 1) // 2,
        "verified_exhaustive": len(exhaustive),
        "verified_plan": len(plan),
        "recall": recall(found, set(exhaustive)),
        "recall_strong": recall(found, {p for p, n in exhaustive.items() if n >= STRONG_INLIERS}),
    }
    if len(sys.argv) == 4:
        scene_file = pathlib.Path(sys.argv[3])
        if not scene_file.is_file():
            sys.exit(f"matching_recall: no scene image list at {scene_file}")
        scene = set(scene_file.read_text().split())
        if not scene & set(names.values()):
            sys.exit(f"matching_recall: no image of {scene_file} is in {database}")
        in_scene = {p for p in exhaustive if names[p[0]] in scene and names[p[1]] in scene}
        scores["recall_scene"] = recall(found, in_scene)
    print(json.dumps(scores))


if __name__ == "__main__":
    main()
