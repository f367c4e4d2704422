# The benchmark data sets in ../shared/data (sourced by the benchmark scripts).
# One line each: name | image folder | camera model | params at full resolution | matcher |
#                ground truth | ground-truth format
# Intrinsics and ground truth as ../shared/data/README.md gives them.
RAMAP_DATASETS=(
  "fountain-P11|strecha/fountain-P11/images|PINHOLE|2759.48,2764.16,1520.69,1006.81|exhaustive|strecha/fountain-P11/gt_dense_cameras|strecha"
  "Herz-Jesus-P8|strecha/Herz-Jesus-P8/images|PINHOLE|2759.48,2764.16,1520.69,1006.81|exhaustive|strecha/Herz-Jesus-P8/gt_dense_cameras|strecha"
  "templeRing|middlebury_templeRing|PINHOLE|1520.4,1525.9,302.32,246.87|exhaustive|middlebury_templeRing/templeR_par.txt|middlebury"
  "lund_door|lund_door/images|SIMPLE_RADIAL|2435.38,648,968,-0.0336422|exhaustive|lund_door/colmap_ground_truth|colmap"
  "kitti07_first160|kitti_3dv_tutorial/kitti07_first160/image_0|PINHOLE|707.0912,707.0912,601.8873,183.1104|sequential|kitti_3dv_tutorial/kitti07_first160/poses_gt.txt|kitti"
  "sceaux_castle|sceaux_castle/images|PINHOLE|2905.88,2905.88,1416,1064|exhaustive||"
)
