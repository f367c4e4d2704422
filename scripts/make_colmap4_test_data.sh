#!/usr/bin/env bash
# Makes tests/data/colmap4/ (committed): a database that COLMAP 4.1.1 itself created from a small
# scene of ramap's synthetic generator, and COLMAP 4.1.1's global_mapper (GLOMAP) model of it, with
# rigs.bin and frames.bin. The tests read both without any COLMAP binary.
#
#   scripts/make_colmap4_test_data.sh     (needs scripts/peers.sh's COLMAP 4.1.1 build)
#
# COLMAP 4.1.1 makes the database as it makes any: `feature_importer` (the scene's keypoints, as
# SIFT text files, with blank images of the camera's size for its image reader) and
# `matches_importer --match_type raw` (the scene's raw matches, true and wrong, verified by COLMAP's
# own two-view geometry estimation).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
ramap=$root/build/ramap
colmap4=$(bash "$root/scripts/peers.sh")
[[ -x $colmap4 ]] || { echo "make_colmap4_test_data: no COLMAP 4.1.1 build" >&2; exit 1; }
out=$root/tests/data/colmap4
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$ramap" synthesize --output_path "$work/scene" --Synthetic.layout sequential \
  --Synthetic.path circle --Synthetic.num_images 10 --Synthetic.num_points 400 \
  --Synthetic.pixel_noise 0.5 --Synthetic.outlier_ratio 0.1 --Synthetic.seed 7 >/dev/null

# Keypoints as COLMAP's SIFT text files (zero descriptors: matches are imported, not computed),
# raw matches as a match list, blank PNG images of the camera's size.
params=$(python3 - "$work" <<'PY'
import sqlite3, struct, sys, zlib, os
work = sys.argv[1]
db = sqlite3.connect(f"{work}/scene/database.db")
(width, height, params), = db.execute("SELECT width, height, params FROM cameras")
os.makedirs(f"{work}/images"); os.makedirs(f"{work}/features")
def png(path, w, h):
    raw = b"".join(b"\0" + bytes(w) for _ in range(h))
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 0, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))
names = {}
for image_id, name in db.execute("SELECT image_id, name FROM images"):
    names[image_id] = name
    png(f"{work}/images/{name}", width, height)
    (rows, cols, data), = db.execute("SELECT rows, cols, data FROM keypoints WHERE image_id = ?", (image_id,))
    values = struct.unpack(f"<{rows * cols}f", data)
    with open(f"{work}/features/{name}.txt", "w") as f:
        f.write(f"{rows} 128\n")
        for r in range(rows):
            x, y = values[r * cols], values[r * cols + 1]
            f.write(f"{x:.6f} {y:.6f} 1 0" + " 0" * 128 + "\n")
with open(f"{work}/matches.txt", "w") as f:
    for pair_id, rows, data in db.execute("SELECT pair_id, rows, data FROM matches WHERE rows > 0"):
        i, j = divmod(pair_id, 2147483647)
        f.write(f"{names[i]} {names[j]}\n")
        m = struct.unpack(f"<{2 * rows}I", data)
        f.write("".join(f"{m[2 * k]} {m[2 * k + 1]}\n" for k in range(rows)) + "\n")
print(",".join(f"{v:.17g}" for v in struct.unpack("<4d", params)))
PY
)

rm -rf "$out"
mkdir -p "$out"
"$colmap4" feature_importer --database_path "$out/database.db" --image_path "$work/images" \
  --import_path "$work/features" --ImageReader.single_camera 1 \
  --ImageReader.camera_model PINHOLE --ImageReader.camera_params "$params" >"$work/log" 2>&1
"$colmap4" matches_importer --database_path "$out/database.db" \
  --match_list_path "$work/matches.txt" --match_type raw >>"$work/log" 2>&1
mkdir -p "$work/sparse"
"$colmap4" global_mapper --database_path "$out/database.db" --image_path "$work/images" \
  --output_path "$work/sparse" --GlobalMapper.ba_refine_focal_length 0 \
  --GlobalMapper.ba_refine_principal_point 0 --GlobalMapper.ba_refine_extra_params 0 \
  >>"$work/log" 2>&1 || { tail -20 "$work/log"; exit 1; }
cp -r "$work/sparse/0" "$out/global_mapper_model"
cp -r "$work/scene/ground_truth" "$out/ground_truth"
sqlite3 "$out/database.db" "PRAGMA user_version" >"$work/version"
cat >"$out/README.md" <<README
Made by \`scripts/make_colmap4_test_data.sh\` with COLMAP 4.1.1 (built from ../shared/peers):
\`database.db\` (user_version $(cat "$work/version")) by COLMAP's feature_importer and
matches_importer --match_type raw from the synthetic scene
\`ramap synthesize --Synthetic.layout sequential --Synthetic.path circle --Synthetic.num_images 10
--Synthetic.num_points 400 --Synthetic.pixel_noise 0.5 --Synthetic.outlier_ratio 0.1
--Synthetic.seed 7\` (its true poses: \`ground_truth/\`, written by ramap), and
\`global_mapper_model/\` by COLMAP's global_mapper on it with fixed intrinsics. Read by
tests/io/colmap4_fixture_test.cc.
README
ls -la "$out" "$out/global_mapper_model"
