// `ramap evaluate --model_path MODEL --ground_truth PATH --ground_truth_format FORMAT`: accuracy of
// a COLMAP model's camera poses against ground truth (eval/pose_metrics.h), as a table on stdout
// and optionally as JSON. Which images count as the input: jobs/model_evaluation.h.
#include <iostream>
#include <string>

#include "options.h"
#include "ramap/jobs/model_evaluation.h"
#include "ramap/util/output_policy.h"

namespace ramap::cli {
namespace {

struct EvaluateCommand {
  ModelEvaluationInput input;
  std::string output_path;
  PoseEvaluationOptions options;
};

const OptionTable<EvaluateCommand>& EvaluateCommandTable() {
  static const OptionTable<EvaluateCommand> table = [] {
    OptionTable<EvaluateCommand> t;
    t.push_back(Required(PathOption<EvaluateCommand>(
        "model_path", [](auto& o) -> auto& { return o.input.model_path; },
        "COLMAP model folder (.bin or .txt)")));
    t.push_back(Required(PathOption<EvaluateCommand>(
        "ground_truth", [](auto& o) -> auto& { return o.input.ground_truth_path; },
        "ground-truth file or folder")));
    t.push_back(Required(ChoiceOption<EvaluateCommand>(
        "ground_truth_format", [](auto& o) -> auto& { return o.input.ground_truth_format; },
        std::vector<std::pair<std::string, GroundTruthFormat>>{
            {"tum", GroundTruthFormat::kTum},
            {"kitti", GroundTruthFormat::kKitti},
            {"strecha", GroundTruthFormat::kStrecha},
            {"middlebury", GroundTruthFormat::kMiddlebury},
            {"colmap", GroundTruthFormat::kColmap}},
        "the ground truth's format")));
    t.push_back(PathOption<EvaluateCommand>(
        "output_path", [](auto& o) -> auto& { return o.output_path; },
        "write the evaluation as JSON here"));
    t.push_back(PathOption<EvaluateCommand>(
        "image_list", [](auto& o) -> auto& { return o.input.image_list_path; },
        "the input images, one name per line (unregistered ones are failures)"));
    t.push_back(PathOption<EvaluateCommand>(
        "database_path", [](auto& o) -> auto& { return o.input.database_path; },
        "COLMAP database whose images are the input (when no --image_list)"));
    AppendOptions(
        PoseEvaluationOptionTable(), [](auto& o) -> auto& { return o.options; }, &t);
    return t;
  }();
  return table;
}

}  // namespace

std::string EvaluateOptionsMarkdown() {
  return OptionTableMarkdown(EvaluateCommandTable(), EvaluateCommand());
}

int RunEvaluate(int argc, char** argv) {
  CLI::App app(
      "Scores a COLMAP model's camera poses against ground truth: registered images, ATE "
      "after Sim(3) alignment, rotation error, relative pose AUC.",
      "ramap evaluate");
  EvaluateCommand c;
  if (const auto code = ParseCommandLine(app, EvaluateCommandTable(), &c, argc, argv)) return *code;
  c.options.Check();
  if (!c.output_path.empty()) {
    CheckFileOutput("--output_path", c.output_path,
                    {c.input.model_path, c.input.ground_truth_path, c.input.image_list_path,
                     c.input.database_path});
  }
  const PoseEvaluation evaluation = EvaluateModel(c.input, c.options);
  std::cout << FormatPoseEvaluation(evaluation);
  if (!c.output_path.empty()) {
    WritePoseEvaluationJson(evaluation, c.output_path);
    std::cout << "Wrote " << c.output_path << "\n";
  }
  return 0;
}

}  // namespace ramap::cli
