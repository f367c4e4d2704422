# `ramap synthesize` along a KITTI ground-truth trajectory with the scale benchmark's settings
# (sourced by scripts/bench_scale.sh and scripts/bench_drives.sh): KITTI's camera (image 0 of the
# odometry calibration), landmarks seen within 40 m, each frame matched with its next 10 and with
# every frame within 8 m that is more than 100 frames away, 2% outlier matches, 4-column keypoints.
#
#   synthesize_kitti_drive RAMAP OUT TRAJECTORY FRAMES NUM_POINTS SEED FACADE_DISTANCE ALIASED \
#                          [MORE --Synthetic OPTIONS]
#   (FRAMES 0: the whole trajectory; FACADE_DISTANCE 0: landmarks anywhere in view; ALIASED: the
#   share of pairs aliased, 0-40 deg off unless more options say otherwise)
synthesize_kitti_drive() {
  local ramap=$1 out=$2 trajectory=$3 frames=$4 num_points=$5 seed=$6 facade_distance=$7
  local aliased=$8
  shift 8
  "$ramap" synthesize --output_path "$out" \
    --Synthetic.trajectory_path "$trajectory" --Synthetic.num_images "$frames" \
    --Synthetic.camera_model PINHOLE --Synthetic.camera_params 718.856,718.856,607.19,185.2 \
    --Synthetic.width 1241 --Synthetic.height 376 --Synthetic.prior_focal_length 1 \
    --Synthetic.num_points "$num_points" --Synthetic.max_view_distance 40 \
    --Synthetic.overlap 10 --Synthetic.loop_radius_m 8 --Synthetic.loop_min_frame_gap 100 \
    --Synthetic.loop_max_angle_deg 180 --Synthetic.aliased_pair_ratio "$aliased" \
    --Synthetic.outlier_ratio 0.02 --Synthetic.facade_distance_m "$facade_distance" \
    --Synthetic.keypoint_columns 4 --Synthetic.seed "$seed" "$@"
}
