// The options of `ramap synthesize` on the command line (--Synthetic.*), as SyntheticSceneOptions.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "ramap/synthetic/synthetic_scene.h"

namespace ramap::cli {

// The options given as text, converted once parsing is done.
struct SceneOptionText {
  std::string layout = "sequential";
  std::string path = "line";
  std::string trajectory_path;
  std::string camera_model;
  std::string camera_params = "500,500,320,240";
  bool prior_focal_length = false;
};

void AddSceneOptions(CLI::App& app, SyntheticSceneOptions* options, SceneOptionText* text);

// Converts the text options into `options` and checks them. A trajectory file replaces the
// generated path; without --Synthetic.num_images (`num_images_given`) all its poses are taken.
void FinishSceneOptions(const SceneOptionText& text, bool num_images_given,
                        SyntheticSceneOptions* options);

}  // namespace ramap::cli
