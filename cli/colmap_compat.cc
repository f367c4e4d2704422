#include "colmap_compat.h"

#include <array>

namespace ramap::cli {
namespace {

struct Alias {
  const char* colmap;
  const char* ramap;  // nullptr: accepted and dropped, for the reason below
  const char* why_ignored = "ramap runs on the CPU";
};

// COLMAP 3.8's names and COLMAP 4.1.1's (its option manager), as the peers' sources give them.
constexpr std::array<Alias, 30> kAliases = {{
    // Feature extraction: SiftExtraction (3.x) became FeatureExtraction (4.x) for what is not
    // specific to SIFT.
    {"--SiftExtraction.max_image_size", "--FeatureExtraction.max_image_size"},
    {"--SiftExtraction.max_num_features", "--FeatureExtraction.max_num_features"},
    {"--SiftExtraction.num_threads", "--FeatureExtraction.num_threads"},
    {"--SiftExtraction.use_gpu", nullptr},
    {"--SiftExtraction.gpu_index", nullptr},
    {"--FeatureExtraction.use_gpu", nullptr},
    {"--FeatureExtraction.gpu_index", nullptr},
    // Matching and verification: SiftMatching (3.x), FeatureMatching and TwoViewGeometry (4.x).
    {"--SiftMatching.max_ratio", "--Matching.max_ratio"},
    {"--SiftMatching.cross_check", "--Matching.cross_check"},
    {"--SiftMatching.max_error", "--Matching.max_error_px"},
    {"--SiftMatching.min_num_inliers", "--Matching.min_num_inliers"},
    {"--SiftMatching.num_threads", "--Matching.num_threads"},
    {"--SiftMatching.use_gpu", nullptr},
    {"--SiftMatching.gpu_index", nullptr},
    {"--FeatureMatching.num_threads", "--Matching.num_threads"},
    {"--FeatureMatching.use_gpu", nullptr},
    {"--FeatureMatching.gpu_index", nullptr},
    {"--TwoViewGeometry.max_error", "--Matching.max_error_px"},
    {"--TwoViewGeometry.min_num_inliers", "--Matching.min_num_inliers"},
    {"--SequentialMatching.overlap", "--Matching.overlap"},
    {"--ExhaustiveMatching.block_size", nullptr,
     "ramap screens and matches every pair in one pass"},
    {"--VocabTreeMatching.vocab_tree_path", nullptr,
     "ramap trains its retrieval vocabulary on the images' own descriptors"},
    {"--VocabTreeMatching.num_images", "--Matching.retrieval_num_neighbors"},
    // The mapper's global bundle adjustment.
    {"--Mapper.ba_global_function_tolerance", "--BundleAdjustment.function_tolerance"},
    {"--Mapper.ba_global_max_num_iterations", "--BundleAdjustment.max_num_iterations"},
    {"--Mapper.ba_refine_focal_length", "--BundleAdjustment.refine_focal_length"},
    {"--Mapper.ba_refine_principal_point", "--BundleAdjustment.refine_principal_point"},
    {"--Mapper.ba_refine_extra_params", "--BundleAdjustment.refine_extra_params"},
    {"--Mapper.ba_use_gpu", nullptr},
    {"--Mapper.ba_gpu_index", nullptr},
}};

const Alias* FindAlias(const std::string& name) {
  for (const Alias& alias : kAliases) {
    if (name == alias.colmap) return &alias;
  }
  return nullptr;
}

}  // namespace

std::vector<std::string> TranslateColmapOptions(const std::vector<std::string>& args,
                                                std::ostream& notes) {
  std::vector<std::string> out;
  for (size_t k = 0; k < args.size(); ++k) {
    const std::string& arg = args[k];
    const size_t equals = arg.find('=');
    const bool inline_value = arg.rfind("--", 0) == 0 && equals != std::string::npos;
    const std::string name = inline_value ? arg.substr(0, equals) : arg;
    const Alias* alias = FindAlias(name);
    if (alias == nullptr) {
      out.push_back(arg);
      continue;
    }
    // The value is in the same argument, or the next one when that is not an option.
    std::string value;
    if (inline_value) {
      value = arg.substr(equals + 1);
    } else if (k + 1 < args.size() && args[k + 1].rfind("--", 0) != 0) {
      value = args[++k];
    }
    if (alias->ramap == nullptr) {
      notes << "ramap: note: " << name << (value.empty() ? "" : " " + value)
            << " ignored: " << alias->why_ignored << "\n";
      continue;
    }
    notes << "ramap: note: " << name << " read as " << alias->ramap << "\n";
    out.push_back(alias->ramap);
    if (!value.empty() || inline_value) out.push_back(value);
  }
  return out;
}

}  // namespace ramap::cli
