#!/usr/bin/env bash
# ramap as the `colmap` executable of nerfstudio and 3D Gaussian Splatting: the command lines that
# nerfstudio's ns-process-data (COLMAP >= 3.7 path, exhaustive matching) and 3DGS's convert.py
# issue, word for word with the executable replaced, on real images; the same lines with COLMAP
# 3.8 (CPU: --SiftExtraction.use_gpu 0, as convert.py --no_gpu) timed beside them. Then what each
# tool reads next is checked: sparse/0 for nerfstudio; images/ and sparse/0 with PINHOLE cameras
# and undistorted images of the cameras' size for 3DGS; and the poses against the ground truth.
#
#   scripts/drop_in.sh [NAME ...]     (default: templeRing Herz-Jesus-P8)
#   scripts/drop_in.sh --one ramap|colmap nerfstudio|convert NAME WORK_DIR
#                                     (one sequence alone, into a fresh WORK_DIR: for timing pairs)
#
# Settings: RAMAP_DATA_DIR (default ../shared/data), RAMAP_BENCH_DIR (default build/bench),
# RAMAP_DROP_IN_COLMAP=0 leaves COLMAP 3.8 out.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
data_dir=${RAMAP_DATA_DIR:-$root/../shared/data}
bench_dir=${RAMAP_BENCH_DIR:-$root/build/bench}/drop_in
ramap=$root/build/ramap
with_colmap=${RAMAP_DROP_IN_COLMAP:-1}
command -v colmap >/dev/null || with_colmap=0
source "$root/scripts/datasets/list.sh"
names=("$@")
((${#names[@]})) || names=(templeRing Herz-Jesus-P8)

elapsed() {  # seconds since $1 (date +%s%N)
  awk -v a="$1" -v b="$(date +%s%N)" 'BEGIN { printf "%.1f", (b - a) / 1e9 }'
}

# nerfstudio's run_colmap (colmap_utils.py): extractor, exhaustive matcher, mapper, then
# bundle_adjuster refining the principal point. $1 executable, $2 images, $3 colmap_dir, $4 gpu.
nerfstudio() {
  local exe=$1 images=$2 dir=$3 gpu=$4
  rm -f "$dir/database.db"
  $exe feature_extractor --database_path "$dir/database.db" --image_path "$images" \
    --ImageReader.single_camera 1 --ImageReader.camera_model OPENCV --SiftExtraction.use_gpu "$gpu"
  $exe exhaustive_matcher --database_path "$dir/database.db" --SiftMatching.use_gpu "$gpu"
  mkdir -p "$dir/sparse"
  $exe mapper --database_path "$dir/database.db" --image_path "$images" \
    --output_path "$dir/sparse" --Mapper.ba_global_function_tolerance=1e-6
  $exe bundle_adjuster --input_path "$dir/sparse/0" --output_path "$dir/sparse/0" \
    --BundleAdjustment.refine_principal_point 1
}

# 3DGS's convert.py: the same front end into distorted/, model_aligner to +Z up, then
# image_undistorter into the source folder, and sparse/* moved into sparse/0.
# $1 executable, $2 source folder (holding input/), $3 gpu.
convert_py() {
  local exe=$1 source=$2 gpu=$3
  mkdir -p "$source/distorted/sparse"
  $exe feature_extractor --database_path "$source/distorted/database.db" \
    --image_path "$source/input" --ImageReader.single_camera 1 \
    --ImageReader.camera_model OPENCV --SiftExtraction.use_gpu "$gpu"
  $exe exhaustive_matcher --database_path "$source/distorted/database.db" \
    --SiftMatching.use_gpu "$gpu"
  $exe mapper --database_path "$source/distorted/database.db" --image_path "$source/input" \
    --output_path "$source/distorted/sparse" --Mapper.ba_global_function_tolerance=0.000001
  $exe model_aligner --input_path "$source/distorted/sparse/0" \
    --database_path "$source/distorted/database.db" --alignment_max_error 0.1 \
    --alignment_type plane --output_path "$source/distorted/sparse/0"
  $exe image_undistorter --image_path "$source/input" --input_path "$source/distorted/sparse/0" \
    --output_path "$source" --output_type COLMAP
  mkdir -p "$source/sparse/0"
  find "$source/sparse" -maxdepth 1 -type f -exec mv {} "$source/sparse/0/" \;
}

# What 3DGS reads: every camera PINHOLE, every registered image in images/ at its camera's size.
check_3dgs_layout() {
  python3 - "$1" <<'PY'
import struct, sys, os, zlib
src = sys.argv[1]
def read(path):
    return open(path, "rb").read()
cams = read(f"{src}/sparse/0/cameras.bin")
n, = struct.unpack_from("<Q", cams, 0); off = 8; size = {}
for _ in range(n):
    cid, model, w, h = struct.unpack_from("<IiQQ", cams, off); off += 24
    assert model == 1, f"camera {cid} is model {model}, not PINHOLE"
    off += 4 * 8; size[cid] = (w, h)
imgs = read(f"{src}/sparse/0/images.bin")
n, = struct.unpack_from("<Q", imgs, 0); off = 8; bad = 0
for _ in range(n):
    off += 4 + 7 * 8; cid, = struct.unpack_from("<I", imgs, off); off += 4
    end = imgs.index(b"\0", off); name = imgs[off:end].decode(); off = end + 1
    k, = struct.unpack_from("<Q", imgs, off); off += 8 + k * 24
    path = f"{src}/images/{name}"
    data = read(path)
    if data[:8] == b"\x89PNG\r\n\x1a\n":
        w, h = struct.unpack_from(">II", data, 16)
    else:  # JPEG: the first start-of-frame marker
        i = 2
        while True:
            marker, length = data[i + 1], struct.unpack_from(">H", data, i + 2)[0]
            if marker in (0xC0, 0xC1, 0xC2):
                h, w = struct.unpack_from(">HH", data, i + 5); break
            i += 2 + length
    if (w, h) != size[cid]: bad += 1
print(f"{n} images, {len(size)} PINHOLE camera(s), {bad} of another size than their camera")
sys.exit(1 if bad else 0)
PY
}

evaluate() {  # model database -> "registered | AUC@3 | rot. median"
  local report=$1.eval.json
  "$ramap" evaluate --model_path "$1" --ground_truth "$data_dir/$gt" \
    --ground_truth_format "$gt_format" --database_path "$2" --output_path "$report" >/dev/null 2>&1 ||
    { echo "evaluation failed | | "; return; }
  python3 - "$report" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
print(f"{r['num_registered']} / {r['num_images']} | {100 * r['relative']['auc_by_threshold_deg']['3']:.1f} | "
      f"{r['rotation_error_deg']['median']:.3f}")
PY
}

# One sequence alone, e.g. under a timer that pairs ramap's run with COLMAP's.
if [[ ${1:-} == --one ]]; then
  [[ $# == 5 ]] || { echo "usage: drop_in.sh --one ramap|colmap nerfstudio|convert NAME WORK_DIR" >&2; exit 2; }
  exe=$ramap gpu=1
  [[ $2 == colmap ]] && exe=colmap && gpu=0
  for entry in "${RAMAP_DATASETS[@]}"; do
    IFS='|' read -r name images _ <<<"$entry"
    [[ $name == "$4" ]] || continue
    rm -rf "$5" && mkdir -p "$5"
    if [[ $3 == nerfstudio ]]; then
      nerfstudio "$exe" "$data_dir/$images" "$5" "$gpu" >"$5.log" 2>&1
    else
      ln -s "$data_dir/$images" "$5/input"
      convert_py "$exe" "$5" "$gpu" >"$5.log" 2>&1
    fi
    exit 0
  done
  echo "drop_in: no data set $4" >&2
  exit 2
fi

echo "| data set | tool's sequence | executable | time (s) | registered | AUC@3 | rot. err. median (deg) | what the tool reads next |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- |"
for entry in "${RAMAP_DATASETS[@]}"; do
  IFS='|' read -r name images _ _ _ gt gt_format <<<"$entry"
  [[ " ${names[*]} " == *" $name "* ]] || continue
  if [[ ! -d $data_dir/$images ]]; then
    echo "drop_in: $data_dir/$images not found; $name skipped" >&2
    continue
  fi
  executables=(ramap)
  ((with_colmap)) && executables+=(colmap)
  for exe_name in "${executables[@]}"; do
    exe=$ramap gpu=1
    [[ $exe_name == colmap ]] && exe=colmap && gpu=0
    work=$bench_dir/$name/$exe_name
    rm -rf "$work" && mkdir -p "$work/nerfstudio" "$work/3dgs"
    start=$(date +%s%N)
    if nerfstudio "$exe" "$data_dir/$images" "$work/nerfstudio" "$gpu" >"$work/nerfstudio.log" 2>&1; then
      seconds=$(elapsed "$start")
      reads="sparse/0 read: $(python3 -c "import struct;d=open('$work/nerfstudio/sparse/0/cameras.bin','rb').read();print(['SIMPLE_PINHOLE','PINHOLE','SIMPLE_RADIAL','RADIAL','OPENCV'][struct.unpack_from('<i',d,12)[0]],'camera')")"
      echo "| $name | nerfstudio | $exe_name | $seconds | $(evaluate "$work/nerfstudio/sparse/0" "$work/nerfstudio/database.db") | $reads |"
    else
      echo "| $name | nerfstudio | $exe_name | failed (log: $work/nerfstudio.log) | | | | |"
    fi
    # convert.py wants the images in SOURCE/input; a link leaves the data set as it is.
    ln -s "$data_dir/$images" "$work/3dgs/input"
    start=$(date +%s%N)
    if convert_py "$exe" "$work/3dgs" "$gpu" >"$work/3dgs.log" 2>&1; then
      seconds=$(elapsed "$start")
      layout=$(check_3dgs_layout "$work/3dgs" 2>&1 || true)
      echo "| $name | 3DGS convert.py | $exe_name | $seconds | $(evaluate "$work/3dgs/sparse/0" "$work/3dgs/distorted/database.db") | $layout |"
    else
      echo "| $name | 3DGS convert.py | $exe_name | failed (log: $work/3dgs.log) | | | | |"
    fi
  done
done
