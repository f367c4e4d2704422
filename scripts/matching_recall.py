#!/usr/bin/env python3
"""How many of the pairs that exhaustive matching verifies ramap's own matching plan found.

    matching_recall.py RAMAP_BINARY DATABASE [SCENE_IMAGES_TXT]

DATABASE is a COLMAP database that `ramap reconstruct` (or `ramap matcher` in its default mode)
matched: its verified pairs are the plan's. A copy of it, its matches removed, is matched again
with every pair tried (`--Matching.mode exhaustive --Matching.preemptive_num_features 0`), the
same features and verification. Prints one JSON object:
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


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    ramap, database = sys.argv[1], pathlib.Path(sys.argv[2])
    if not database.is_file():
        sys.exit(f"matching_recall: no database at {database}")
    plan = verified_pairs(database)
    names = image_names(database)
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
        subprocess.run([ramap, "matcher", "--database_path", str(exhaustive_db), "--log_level", "0",
                        "--Matching.mode", "exhaustive", "--Matching.preemptive_num_features", "0"],
                       check=True, stdout=subprocess.DEVNULL)
        exhaustive = verified_pairs(exhaustive_db)
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
        scene = set(pathlib.Path(sys.argv[3]).read_text().split())
        in_scene = {p for p in exhaustive if names[p[0]] in scene and names[p[1]] in scene}
        scores["recall_scene"] = recall(found, in_scene)
    print(json.dumps(scores))


if __name__ == "__main__":
    main()
