#include "test_support.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>

#include "ramap/util/error.h"

namespace ramap::test {
namespace fs = std::filesystem;

std::string SharedDataDir() {
  if (const char* env = std::getenv("RAMAP_DATA_DIR"); env != nullptr && *env != '\0') return env;
  return RAMAP_SHARED_DATA_DIR;
}

std::string SharedDataPath(const std::string& relative) {
  const fs::path path = fs::path(SharedDataDir()) / relative;
  return fs::exists(path) ? path.string() : std::string();
}

bool ColmapAvailable() {
  static const bool available = RunCommand("command -v colmap").exit_code == 0;
  return available;
}

std::string Colmap4Binary() {
  const char* given = std::getenv("RAMAP_COLMAP4");
  const std::string path =
      given != nullptr && *given != '\0'
          ? std::string(given)
          : std::string(RAMAP_SOURCE_DIR) + "/build-peers/build/src/colmap/exe/colmap";
  return std::filesystem::exists(path) ? path : "";
}

std::string RamapBinary() { return RAMAP_CLI_PATH; }

std::string RamapCommand() { return "'" + RamapBinary() + "' "; }

std::string ReadFileBytes(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
}

nlohmann::json ReadJsonFile(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

ColmapRun HerzJesusFourImages(const std::string& image_dir) {
  ColmapRun run;
  run.image_dir = image_dir;
  run.image_names = {"0000.jpg", "0001.jpg", "0002.jpg", "0003.jpg"};
  run.camera_params = "2759.48,2764.16,1520.69,1006.81";
  run.max_image_size = 640;
  return run;
}

nlohmann::json ReportPageData(const std::string& report_path) {
  const std::string page = ReadFileBytes(report_path);
  const std::string open = "<script type=\"application/json\" id=\"ramap-data\">";
  const size_t begin = page.find(open);
  const size_t end = begin == std::string::npos ? begin : page.find("</script>", begin);
  if (end == std::string::npos) {
    ADD_FAILURE() << report_path << " holds no page data";
    return nullptr;
  }
  return nlohmann::json::parse(page.substr(begin + open.size(), end - begin - open.size()));
}

void ExpectInputError(const std::function<void()>& action, const std::vector<std::string>& parts) {
  try {
    action();
    ADD_FAILURE() << "no InputError; expected one mentioning '" << parts.front() << "'";
  } catch (const InputError& error) {
    for (const std::string& part : parts) {
      EXPECT_NE(std::string(error.what()).find(part), std::string::npos)
          << "message '" << error.what() << "' lacks '" << part << "'";
    }
  }
}

CommandResult RunCommand(const std::string& command_line) {
  CommandResult result;
  const std::string full = command_line + " 2>&1";
  FILE* pipe = popen(full.c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 4096> buffer;
  size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
    result.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

TempDir::TempDir() {
  std::string pattern = (fs::temp_directory_path() / "ramap-test-XXXXXX").string();
  path_ = mkdtemp(pattern.data());
}

TempDir::~TempDir() {
  std::error_code ec;
  fs::remove_all(path_, ec);
}

}  // namespace ramap::test

namespace ramap::test {
namespace {

std::string CacheRoot() {
  // $RAMAP_TEST_CACHE_DIR lets a second build (the sanitizer one) share the COLMAP runs.
  const char* env = std::getenv("RAMAP_TEST_CACHE_DIR");
  const fs::path root = env != nullptr && *env != '\0'
                            ? fs::path(env)
                            : fs::path(RAMAP_CLI_PATH).parent_path() / "test-cache";
  fs::create_directories(root);
  return root.string();
}

std::string RunKey(const ColmapRun& run) {
  std::string key = run.image_dir + "|" + run.camera_model + "|" + run.camera_params + "|" +
                    std::to_string(run.max_image_size) + "|" +
                    (run.sequential_matching ? "seq" : "exh");
  for (const std::string& name : run.image_names) key += "|" + name;
  return std::to_string(std::hash<std::string>{}(key));
}

// Holds an exclusive lock on `path` while alive, so parallel ctest processes build a cache once.
class FileLock {
 public:
  explicit FileLock(const std::string& path) : file_(fopen(path.c_str(), "a")) {
    if (file_) lockf(fileno(file_), F_LOCK, 0);
  }
  ~FileLock() {
    if (file_) {
      lockf(fileno(file_), F_ULOCK, 0);
      fclose(file_);
    }
  }

 private:
  FILE* file_;
};

bool Run(const std::string& command_line, const std::string& log_path) {
  const CommandResult result = RunCommand(command_line + " > '" + log_path + "' 2>&1");
  if (result.exit_code != 0) {
    ADD_FAILURE() << "command failed (" << result.exit_code << "): " << command_line
                  << "\nlog: " << log_path;
  }
  return result.exit_code == 0;
}

}  // namespace

std::string CachedColmapDatabase(const ColmapRun& run) {
  const std::string dir = CacheRoot() + "/colmap-" + RunKey(run);
  const std::string database = dir + "/database.db";
  FileLock lock(dir + ".lock");
  if (fs::exists(dir + "/database.done")) return database;
  fs::remove_all(dir);
  fs::create_directories(dir + "/images");
  // A folder of links holds exactly the subset, so COLMAP sees only those images.
  for (const auto& entry : fs::directory_iterator(run.image_dir)) {
    const std::string name = entry.path().filename().string();
    const bool wanted = run.image_names.empty()
                            ? (entry.path().extension() != ".txt" && entry.is_regular_file())
                            : std::find(run.image_names.begin(), run.image_names.end(), name) !=
                                  run.image_names.end();
    if (wanted) fs::create_symlink(fs::absolute(entry.path()), dir + "/images/" + name);
  }
  const std::string common = " --database_path '" + database + "'";
  if (!Run("colmap feature_extractor" + common + " --image_path '" + dir + "/images'" +
               " --ImageReader.single_camera 1 --ImageReader.camera_model " + run.camera_model +
               " --ImageReader.camera_params " + run.camera_params +
               " --SiftExtraction.use_gpu 0 --SiftExtraction.num_threads 2" +
               " --SiftExtraction.max_image_size " + std::to_string(run.max_image_size),
           dir + "/extract.log")) {
    return "";
  }
  const std::string matcher = run.sequential_matching ? "sequential_matcher" : "exhaustive_matcher";
  if (!Run("colmap " + matcher + common + " --SiftMatching.use_gpu 0 --SiftMatching.num_threads 2",
           dir + "/match.log")) {
    return "";
  }
  std::ofstream(dir + "/database.done") << "ok\n";
  return database;
}

std::string CachedColmapModel(const ColmapRun& run) {
  const std::string database = CachedColmapDatabase(run);
  if (database.empty()) return "";
  const std::string dir = fs::path(database).parent_path().string();
  FileLock lock(dir + ".model.lock");
  const std::string model = dir + "/sparse/0";
  if (fs::exists(dir + "/model.done")) return model;
  fs::remove_all(dir + "/sparse");
  fs::create_directories(dir + "/sparse");
  if (!Run("colmap mapper --database_path '" + database + "' --image_path '" + dir + "/images'" +
               " --output_path '" + dir + "/sparse' --Mapper.num_threads 2" +
               " --Mapper.ba_refine_focal_length 0 --Mapper.ba_refine_principal_point 0" +
               " --Mapper.ba_refine_extra_params 0",
           dir + "/mapper.log")) {
    return "";
  }
  if (!fs::exists(model + "/images.bin")) {
    ADD_FAILURE() << "colmap mapper made no model in " << dir << "/sparse";
    return "";
  }
  std::ofstream(dir + "/model.done") << "ok\n";
  return model;
}

SyntheticSceneOptions WithFacadeRepeats(SyntheticSceneOptions options, int num_pairs,
                                        double shift_m) {
  options.num_aliased_pairs = num_pairs;
  options.aliased_min_angle_deg = 0.0;
  options.aliased_max_angle_deg = 0.0;
  options.aliased_max_frame_gap = 8;
  options.aliased_shift_m = shift_m;
  options.aliased_matches_on_tracks = true;
  return options;
}

MapperOptions AveragingOnly() {
  MapperOptions options;
  options.refine = false;
  options.subset_adjustment = false;
  return options;
}

SyntheticSceneOptions NoiseFree(SyntheticLayout layout, SyntheticPath path, int num_images) {
  SyntheticSceneOptions options;
  options.layout = layout;
  options.path = path;
  options.num_images = num_images;
  options.num_points = 1500;
  options.pixel_noise_sigma = 0.0;
  options.outlier_ratio = 0.0;
  options.seed = 11;
  return options;
}

SyntheticSceneOptions NoisyCollection(uint64_t seed) {
  SyntheticSceneOptions options;
  options.layout = SyntheticLayout::kUnordered;
  options.num_images = 16;
  options.num_points = 3000;
  options.pixel_noise_sigma = 0.5;
  options.outlier_ratio = 0.1;
  options.seed = seed;
  return options;
}

PoseEvaluation EvaluateAgainstTruth(const Reconstruction& model, const SyntheticScene& scene) {
  std::vector<std::string> names;
  for (const auto& [id, image] : scene.ground_truth.images) names.push_back(image.name);
  return EvaluatePoses(PosesByName(model), PosesByName(scene.ground_truth), names);
}

SyntheticScene StandstillLineScene() {
  SyntheticSceneOptions options = NoiseFree(SyntheticLayout::kSequential, SyntheticPath::kLine, 30);
  const SyntheticScene line = BuildSyntheticScene(options);
  options.path = SyntheticPath::kGiven;
  for (const auto& [id, image] : line.ground_truth.images) {
    options.given_poses.push_back(image.cam_from_world);
  }
  const Eigen::Vector3d stop = options.given_poses[10].Inverse().translation;
  for (const int frame : {9, 11}) {  // images 10 and 12
    Rigid3d& pose = options.given_poses[frame];
    pose.translation = -(pose.rotation * stop);
  }
  SyntheticScene scene = BuildSyntheticScene(options);
  for (auto it = scene.database.two_view_geometries.begin();
       it != scene.database.two_view_geometries.end();) {
    const TwoViewGeometry& geometry = it->second;
    const bool with_11 = geometry.image_id1 == 11 || geometry.image_id2 == 11;
    const uint32_t other = geometry.image_id1 == 11 ? geometry.image_id2 : geometry.image_id1;
    it = with_11 && other != 10 && other != 12 ? scene.database.two_view_geometries.erase(it)
                                               : std::next(it);
  }
  return scene;
}

Camera VgaPinholeCamera(double fx, double fy) {
  Camera camera;
  camera.camera_id = 1;
  camera.model = CameraModel::kPinhole;
  camera.width = 640;
  camera.height = 480;
  camera.params = {fx, fy, 320, 240};
  return camera;
}

}  // namespace ramap::test
