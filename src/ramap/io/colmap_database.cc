#include "ramap/io/colmap_database.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "ramap/io/colmap_database_schema.h"
#include "ramap/io/database_rigs_priors.h"
#include "ramap/io/sqlite.h"
#include "ramap/util/error.h"
#include "ramap/util/staged_output.h"

namespace ramap {
namespace {

namespace fs = std::filesystem;
using sqlite::BlobView;
using sqlite::Connection;
using sqlite::Statement;

// ramap's own table beside COLMAP's (see the header).
constexpr const char* kMatchConfidenceTable = "ramap_match_confidence";

// Parameter names per model id, in COLMAP's order (for messages).
constexpr const char* kParamNames[] = {
    "f, cx, cy",
    "fx, fy, cx, cy",
    "f, cx, cy, k",
    "f, cx, cy, k1, k2",
    "fx, fy, cx, cy, k1, k2, p1, p2",
    "fx, fy, cx, cy, k1, k2, k3, k4",
    "fx, fy, cx, cy, k1, k2, p1, p2, k3, k4, k5, k6",
    "fx, fy, cx, cy, omega",
    "f, cx, cy, k",
    "f, cx, cy, k1, k2",
    "fx, fy, cx, cy, k1, k2, p1, p2, k3, k4, sx1, sy1",
};

std::string ParamName(CameraModel model, size_t index) {
  std::stringstream names(kParamNames[static_cast<int>(model)]);
  std::string name;
  for (size_t i = 0; i <= index && std::getline(names, name, ','); ++i) {
  }
  while (!name.empty() && name.front() == ' ') name.erase(name.begin());
  if (name == "f" || name == "fx" || name == "fy") name += " (focal length)";
  if (name == "cx" || name == "cy") name += " (principal point)";
  return name;
}

std::string CameraLabel(uint32_t camera_id, CameraModel model) {
  return "camera " + std::to_string(camera_id) + " (" + CameraModelName(model) + ")";
}

std::string ImageLabel(const FeatureDatabase& database, uint32_t image_id) {
  const auto it = database.images.find(image_id);
  if (it == database.images.end()) return "image " + std::to_string(image_id);
  return "image " + std::to_string(image_id) + " '" + it->second.name + "'";
}

std::string PairLabel(const FeatureDatabase& database, uint32_t image_id1, uint32_t image_id2) {
  return "pair (" + ImageLabel(database, image_id1) + ", " + ImageLabel(database, image_id2) + ")";
}

// Checks a camera's model, parameter count and values; `fail` throws with a problem text.
template <typename Fail>
void CheckCamera(const Camera& camera, Fail&& fail) {
  const std::string label = CameraLabel(camera.camera_id, camera.model);
  const size_t expected = NumCameraParams(camera.model);
  if (camera.params.size() != expected) {
    fail(label + ": has " + std::to_string(camera.params.size()) + " parameters, the model has " +
         std::to_string(expected) + " (" + kParamNames[static_cast<int>(camera.model)] + ")");
  }
  for (size_t i = 0; i < camera.params.size(); ++i) {
    if (!std::isfinite(camera.params[i])) {
      std::ostringstream value;
      value << camera.params[i];
      fail(label + ": parameter " + ParamName(camera.model, i) + " is " + value.str() +
           ", not a finite number");
    }
  }
}

// Checks that every match indexes an existing keypoint of its image.
template <typename Fail>
void CheckMatchIndices(const FeatureDatabase& database, const char* table, uint32_t image_id1,
                       uint32_t image_id2, const std::vector<FeatureMatch>& matches, Fail&& fail) {
  const auto NumKeypoints = [&](uint32_t image_id) -> size_t {
    const auto it = database.keypoints.find(image_id);
    return it == database.keypoints.end() ? 0 : it->second.size();
  };
  const size_t num1 = NumKeypoints(image_id1);
  const size_t num2 = NumKeypoints(image_id2);
  for (size_t m = 0; m < matches.size(); ++m) {
    const FeatureMatch& match = matches[m];
    const bool first_bad = match.point2D_idx1 >= num1;
    if (first_bad || match.point2D_idx2 >= num2) {
      const uint32_t image_id = first_bad ? image_id1 : image_id2;
      const uint32_t index = first_bad ? match.point2D_idx1 : match.point2D_idx2;
      fail(std::string(table) + " of " + PairLabel(database, image_id1, image_id2) + ": match " +
           std::to_string(m) + " refers to keypoint " + std::to_string(index) + " of " +
           ImageLabel(database, image_id) + ", which has " +
           std::to_string(first_bad ? num1 : num2) + " keypoints");
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Reading.

class Reader {
 public:
  Reader(const std::string& path, const DatabaseReadOptions& options)
      : path_(path), options_(options), db_(path, Connection::OpenExisting(), path) {}

  FeatureDatabase Read() {
    CheckIsSqlite();
    const DatabaseLayout layout = DetectDatabaseLayout(db_);
    CheckColumns("cameras",
                 {"camera_id", "model", "width", "height", "params", "prior_focal_length"});
    CheckColumns("images", {"image_id", "name", "camera_id"});
    CheckColumns("keypoints", {"image_id", "rows", "cols", "data"});
    if (options_.read_descriptors)
      CheckColumns("descriptors", {"image_id", "rows", "cols", "data"});
    if (options_.read_matches) CheckColumns("matches", {"pair_id", "rows", "cols", "data"});
    CheckColumns("two_view_geometries",
                 {"pair_id", "rows", "cols", "data", "config", "F", "E", "H", "qvec", "tvec"});
    ReadCameras();
    ReadImages(layout.image_prior_columns);
    ReadDatabasePosePriors(db_, layout, &database_);
    if (layout.rigs_and_frames) ReadDatabaseRigsAndFrames(db_, &database_);
    ReadKeypoints();
    if (options_.read_descriptors) ReadDescriptors();
    if (options_.read_matches) ReadMatches();
    ReadTwoViewGeometries();
    ReadMatchConfidence();
    database_.source_path = path_;
    database_.generation = layout.generation;
    return std::move(database_);
  }

 private:
  [[noreturn]] void Fail(const std::string& problem) const { throw InputError(path_, problem); }

  void CheckIsSqlite() {
    // Opening is lazy: the first read of the header tells whether this is an SQLite file.
    try {
      db_.SetQueryOnly();
      Statement statement(db_, "SELECT count(*) FROM sqlite_master");
      statement.Step();
    } catch (const InputError&) {
      Fail("not a readable SQLite database (is it a COLMAP database?): SQLite says '" +
           db_.LastError() + "'");
    }
  }

  void CheckColumns(const std::string& table, const std::vector<std::string>& columns) {
    const std::set<std::string> present = TableColumns(db_, table);
    if (present.empty()) {
      Fail("missing table '" + table + "' (not a COLMAP database, or one from another version?)");
    }
    for (const std::string& column : columns) {
      if (present.count(column) == 0) {
        // COLMAP added the pose columns of two_view_geometries late; other gaps are rarer.
        const bool two_view_table = table == "two_view_geometries";
        Fail("table '" + table + "': missing column '" + column + "'" +
             (two_view_table ? " (database from a COLMAP older than 3.8? ramap reads COLMAP "
                               "3.8-4.x databases)"
                             : " (not a COLMAP database?)"));
      }
    }
  }

  // A blob of rows x cols values of `value_size` bytes; `what` names the item for messages.
  BlobView CheckedBlob(const Statement& row, int rows_column, int cols_column, int data_column,
                       size_t value_size, const std::string& what, int64_t* rows,
                       int64_t* cols) const {
    *rows = row.ColumnInt64(rows_column);
    *cols = row.ColumnInt64(cols_column);
    if (*rows < 0 || *cols < 0 || *rows > (int64_t{1} << 40) || *cols > (int64_t{1} << 20)) {
      Fail(what + ": invalid size " + std::to_string(*rows) + " x " + std::to_string(*cols));
    }
    const BlobView blob = row.ColumnBlob(data_column);
    const size_t expected = static_cast<size_t>(*rows) * static_cast<size_t>(*cols) * value_size;
    if (blob.size != expected) {
      Fail(what + ": data blob has " + std::to_string(blob.size) + " bytes, " +
           std::to_string(*rows) + " x " + std::to_string(*cols) + " values of " +
           std::to_string(value_size) + " bytes need " + std::to_string(expected) +
           (blob.size < expected ? " (truncated?)" : ""));
    }
    return blob;
  }

  uint32_t CheckedImageId(int64_t id, const std::string& table) const {
    if (id < 0 || id >= static_cast<int64_t>(kMaxNumImages)) {
      Fail(table + ": image id " + std::to_string(id) + " out of COLMAP's range");
    }
    const uint32_t image_id = static_cast<uint32_t>(id);
    if (database_.images.count(image_id) == 0) {
      Fail(table + ": row for image id " + std::to_string(id) + ", which is not in table images");
    }
    return image_id;
  }

  // The two image ids of a pair_id, checked to be a valid COLMAP pair of existing images.
  std::pair<uint32_t, uint32_t> CheckedPair(int64_t pair_id, const std::string& table) const {
    const std::string label = table + ": pair_id " + std::to_string(pair_id);
    if (pair_id < 0) Fail(label + " is negative");
    const auto [id1, id2] = PairIdToImagePair(static_cast<uint64_t>(pair_id));
    if (id1 >= id2 || ImagePairToPairId(id1, id2) != static_cast<uint64_t>(pair_id)) {
      Fail(label + " is not a valid COLMAP pair id (i * 2147483647 + j with i < j)");
    }
    for (const uint32_t id : {id1, id2}) {
      if (database_.images.count(id) == 0) {
        Fail(label + " (images " + std::to_string(id1) + ", " + std::to_string(id2) +
             ") refers to image id " + std::to_string(id) + ", which is not in table images");
      }
    }
    return {id1, id2};
  }

  std::vector<FeatureMatch> DecodeMatches(const Statement& row, const std::string& what) const {
    int64_t rows = 0, cols = 0;
    // COLMAP stores empty match lists with any column count; only non-empty ones must be N x 2.
    if (row.ColumnInt64(1) != 0 && row.ColumnInt64(2) != 2) {
      Fail(what + ": matches have " + std::to_string(row.ColumnInt64(2)) + " columns, expected 2");
    }
    const BlobView blob = CheckedBlob(row, 1, 2, 3, sizeof(uint32_t), what, &rows, &cols);
    std::vector<FeatureMatch> matches(static_cast<size_t>(rows));
    static_assert(sizeof(FeatureMatch) == 2 * sizeof(uint32_t));
    if (blob.size > 0) std::memcpy(matches.data(), blob.data, blob.size);
    return matches;
  }

  void ReadCameras() {
    Statement row(
        db_, "SELECT camera_id, model, width, height, params, prior_focal_length FROM cameras");
    while (row.Step()) {
      const int64_t id = row.ColumnInt64(0);
      const std::string label = "camera " + std::to_string(id);
      if (id < 0 || id > static_cast<int64_t>(UINT32_MAX)) Fail(label + ": id out of range");
      const int64_t model_id = row.ColumnInt64(1);
      const std::optional<CameraModel> model = model_id >= 0 && model_id <= 1000
                                                   ? CameraModelFromId(static_cast<int>(model_id))
                                                   : std::nullopt;
      if (!model) {
        Fail(label + ": unknown camera model id " + std::to_string(model_id) +
             " (ramap reads COLMAP's models 0-10)");
      }
      Camera camera;
      camera.camera_id = static_cast<uint32_t>(id);
      camera.model = *model;
      const int64_t width = row.ColumnInt64(2);
      const int64_t height = row.ColumnInt64(3);
      if (width < 0 || height < 0) {
        Fail(CameraLabel(camera.camera_id, camera.model) + ": negative image size");
      }
      camera.width = static_cast<uint64_t>(width);
      camera.height = static_cast<uint64_t>(height);
      const BlobView params = row.ColumnBlob(4);
      const size_t expected_bytes = NumCameraParams(camera.model) * sizeof(double);
      if (params.size != expected_bytes) {
        Fail(CameraLabel(camera.camera_id, camera.model) + ": params blob has " +
             std::to_string(params.size) + " bytes, expected " + std::to_string(expected_bytes) +
             " (" + std::to_string(NumCameraParams(camera.model)) +
             " float64: " + kParamNames[static_cast<int>(camera.model)] + ")");
      }
      camera.params.resize(NumCameraParams(camera.model));
      std::memcpy(camera.params.data(), params.data, params.size);
      camera.has_prior_focal_length = row.ColumnInt64(5) != 0;
      CheckCamera(camera, [this](const std::string& problem) { Fail(problem); });
      database_.cameras.emplace(camera.camera_id, std::move(camera));
    }
  }

  // With `prior_columns`, the priors of COLMAP 3.8's images table too (a database COLMAP 4
  // upgraded keeps them; its pose_priors table, read after, has the last word).
  void ReadImages(bool prior_columns) {
    Statement row(db_, prior_columns
                           ? "SELECT image_id, name, camera_id, prior_qw, prior_qx, prior_qy, "
                             "prior_qz, prior_tx, prior_ty, prior_tz FROM images"
                           : "SELECT image_id, name, camera_id, NULL, NULL, NULL, NULL, NULL, "
                             "NULL, NULL FROM images");
    while (row.Step()) {
      const int64_t id = row.ColumnInt64(0);
      if (id < 0 || id >= static_cast<int64_t>(kMaxNumImages)) {
        Fail("images: image id " + std::to_string(id) + " out of COLMAP's range");
      }
      Image image;
      image.image_id = static_cast<uint32_t>(id);
      image.name = row.ColumnText(1);
      const int64_t camera_id = row.ColumnInt64(2);
      if (camera_id < 0 || camera_id > static_cast<int64_t>(UINT32_MAX) ||
          database_.cameras.count(static_cast<uint32_t>(camera_id)) == 0) {
        Fail("image " + std::to_string(id) + " '" + image.name + "': camera id " +
             std::to_string(camera_id) + " is not in table cameras");
      }
      image.camera_id = static_cast<uint32_t>(camera_id);
      // COLMAP writes an unknown prior as NaN, which SQLite stores as NULL; either means absent.
      const auto Values = [&row](int first, int count, double* values) {
        for (int i = 0; i < count; ++i) {
          if (row.IsNull(first + i)) return false;
          values[i] = row.ColumnDouble(first + i);
          if (!std::isfinite(values[i])) return false;
        }
        return true;
      };
      double q[4];
      if (Values(3, 4, q)) image.prior_rotation = Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
      double t[3];
      if (Values(7, 3, t)) image.prior_translation = Eigen::Vector3d(t[0], t[1], t[2]);
      // COLMAP's schema makes names unique; a database without that index could hold two images
      // of one name, which no model can tell apart.
      const auto [named, fresh] = names_.emplace(image.name, image.image_id);
      if (!fresh) {
        Fail("images: image ids " + std::to_string(named->second) + " and " + std::to_string(id) +
             " have the same name '" + image.name + "'");
      }
      database_.images.emplace(image.image_id, std::move(image));
    }
  }

  void ReadKeypoints() {
    Statement row(db_, "SELECT image_id, rows, cols, data FROM keypoints");
    while (row.Step()) {
      const uint32_t image_id = CheckedImageId(row.ColumnInt64(0), "keypoints");
      const std::string what = "keypoints of " + ImageLabel(database_, image_id);
      const int64_t cols = row.ColumnInt64(2);
      if (cols != 2 && cols != 4 && cols != 6) {
        Fail(what + ": " + std::to_string(cols) + " columns, expected 2, 4 or 6");
      }
      int64_t rows = 0, checked_cols = 0;
      const BlobView blob = CheckedBlob(row, 1, 2, 3, sizeof(float), what, &rows, &checked_cols);
      Keypoints& keypoints = database_.keypoints[image_id];
      keypoints.num_cols = static_cast<int>(cols);
      keypoints.data.resize(static_cast<size_t>(rows * cols));
      if (blob.size > 0) std::memcpy(keypoints.data.data(), blob.data, blob.size);
    }
  }

  void ReadDescriptors() {
    Statement row(db_, "SELECT image_id, rows, cols, data FROM descriptors");
    while (row.Step()) {
      const uint32_t image_id = CheckedImageId(row.ColumnInt64(0), "descriptors");
      const std::string what = "descriptors of " + ImageLabel(database_, image_id);
      int64_t rows = 0, cols = 0;
      const BlobView blob = CheckedBlob(row, 1, 2, 3, sizeof(uint8_t), what, &rows, &cols);
      if (rows > 0 && cols == 0) Fail(what + ": zero columns");
      // Descriptor r belongs to keypoint r: the matcher indexes keypoints by descriptor row.
      const auto keypoints = database_.keypoints.find(image_id);
      const int64_t num_keypoints = keypoints == database_.keypoints.end()
                                        ? 0
                                        : static_cast<int64_t>(keypoints->second.size());
      if (rows != num_keypoints) {
        Fail(what + ": " + std::to_string(rows) + " descriptors for " +
             std::to_string(num_keypoints) + " keypoints (must be one per keypoint)");
      }
      Descriptors& descriptors = database_.descriptors[image_id];
      descriptors.num_cols = static_cast<int>(cols);
      descriptors.data.assign(static_cast<const uint8_t*>(blob.data),
                              static_cast<const uint8_t*>(blob.data) + blob.size);
    }
  }

  void ReadMatches() {
    Statement row(db_, "SELECT pair_id, rows, cols, data FROM matches");
    while (row.Step()) {
      const int64_t pair_id = row.ColumnInt64(0);
      const auto [id1, id2] = CheckedPair(pair_id, "matches");
      std::vector<FeatureMatch> matches =
          DecodeMatches(row, "matches of " + PairLabel(database_, id1, id2));
      CheckMatchIndices(database_, "matches", id1, id2, matches,
                        [this](const std::string& problem) { Fail(problem); });
      database_.matches.emplace(static_cast<uint64_t>(pair_id), std::move(matches));
    }
  }

  // A fixed-size float64 blob: filled into `values` when present, false when NULL or empty.
  bool FixedBlob(const Statement& row, int column, size_t count, double* values,
                 const std::string& what) const {
    const BlobView blob = row.ColumnBlob(column);
    if (blob.size == 0) return false;
    if (blob.size != count * sizeof(double)) {
      Fail(what + ": blob has " + std::to_string(blob.size) + " bytes, expected " +
           std::to_string(count * sizeof(double)) + " (" + std::to_string(count) + " float64)");
    }
    std::memcpy(values, blob.data, blob.size);
    for (size_t i = 0; i < count; ++i) {
      if (!std::isfinite(values[i])) Fail(what + ": holds a value that is not finite");
    }
    return true;
  }

  void ReadTwoViewGeometries() {
    Statement row(db_,
                  "SELECT pair_id, rows, cols, data, config, F, E, H, qvec, tvec FROM "
                  "two_view_geometries");
    while (row.Step()) {
      const int64_t pair_id = row.ColumnInt64(0);
      const auto [id1, id2] = CheckedPair(pair_id, "two_view_geometries");
      const std::string what = "two_view_geometries of " + PairLabel(database_, id1, id2);
      TwoViewGeometry geometry;
      geometry.image_id1 = id1;
      geometry.image_id2 = id2;
      const int64_t config = row.ColumnInt64(4);
      if (config < 0 || config > static_cast<int>(TwoViewConfig::kCalibratedRig)) {
        Fail(what + ": unknown configuration type " + std::to_string(config) +
             " (COLMAP's types are 0-9)");
      }
      geometry.config = static_cast<TwoViewConfig>(config);
      geometry.inlier_matches = DecodeMatches(row, what);
      CheckMatchIndices(database_, "two_view_geometries", id1, id2, geometry.inlier_matches,
                        [this](const std::string& problem) { Fail(problem); });
      using RowMajor3d = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
      RowMajor3d matrix;
      if (FixedBlob(row, 5, 9, matrix.data(), what + ", F")) geometry.F = matrix;
      if (FixedBlob(row, 6, 9, matrix.data(), what + ", E")) geometry.E = matrix;
      if (FixedBlob(row, 7, 9, matrix.data(), what + ", H")) geometry.H = matrix;
      double q[4];
      // An all-zero qvec means "no pose estimated" (nothing to rotate by): identity.
      if (FixedBlob(row, 8, 4, q, what + ", qvec") &&
          (q[0] != 0 || q[1] != 0 || q[2] != 0 || q[3] != 0)) {
        geometry.cam2_from_cam1.rotation = Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
      }
      double t[3];
      if (FixedBlob(row, 9, 3, t, what + ", tvec")) {
        geometry.cam2_from_cam1.translation = Eigen::Vector3d(t[0], t[1], t[2]);
      }
      database_.two_view_geometries.emplace(static_cast<uint64_t>(pair_id), std::move(geometry));
    }
  }

  // ramap's table of descriptor ratios, when the database has it (see the header).
  void ReadMatchConfidence() {
    Statement exists(db_, "SELECT count(*) FROM sqlite_master WHERE type = 'table' AND name = ?");
    exists.BindText(1, kMatchConfidenceTable);
    if (!exists.Step() || exists.ColumnInt64(0) == 0) return;
    CheckColumns(kMatchConfidenceTable, {"pair_id", "rows", "data"});
    Statement row(db_, std::string("SELECT pair_id, rows, data FROM ") + kMatchConfidenceTable);
    while (row.Step()) {
      const int64_t pair_id = row.ColumnInt64(0);
      const auto [id1, id2] = CheckedPair(pair_id, kMatchConfidenceTable);
      const std::string what =
          std::string(kMatchConfidenceTable) + " of " + PairLabel(database_, id1, id2);
      const auto geometry = database_.two_view_geometries.find(static_cast<uint64_t>(pair_id));
      if (geometry == database_.two_view_geometries.end()) {
        Fail(what + ": the pair has no two_view_geometries row");
      }
      const int64_t rows = row.ColumnInt64(1);
      const BlobView blob = row.ColumnBlob(2);
      if (rows != static_cast<int64_t>(geometry->second.inlier_matches.size()) ||
          blob.size != static_cast<size_t>(rows) * sizeof(float)) {
        Fail(what + ": " + std::to_string(rows) + " rows in " + std::to_string(blob.size) +
             " bytes for " + std::to_string(geometry->second.inlier_matches.size()) +
             " inlier matches");
      }
      std::vector<float>& ratios = geometry->second.inlier_ratios;
      ratios.resize(rows);
      std::memcpy(ratios.data(), blob.data, blob.size);
      for (const float ratio : ratios) {
        if (!(ratio >= 0 && ratio <= 1)) Fail(what + ": a ratio outside [0, 1]");
      }
    }
  }

  const std::string path_;
  const DatabaseReadOptions options_;
  Connection db_;
  FeatureDatabase database_;
  std::map<std::string, uint32_t> names_;  // image name -> id, to refuse duplicates
};

// ---------------------------------------------------------------------------------------------
// Writing.

// Everything the reader would reject, checked before a byte is written.
namespace {

// Throws InputError(path, "cannot write the database: problem").
struct WriteFailure {
  const std::string& path;
  [[noreturn]] void operator()(const std::string& problem) const {
    throw InputError(path, "cannot write the database: " + problem);
  }
};

void CheckWritableCamerasAndImages(const FeatureDatabase& database, const WriteFailure& Fail) {
  for (const auto& [camera_id, camera] : database.cameras) {
    if (camera.camera_id != camera_id) {
      Fail("camera keyed " + std::to_string(camera_id) + " has camera_id " +
           std::to_string(camera.camera_id));
    }
    CheckCamera(camera, Fail);
  }
  std::set<std::string> names;
  for (const auto& [image_id, image] : database.images) {
    const std::string label = ImageLabel(database, image_id);
    if (image.image_id != image_id) {
      Fail("image keyed " + std::to_string(image_id) + " has image_id " +
           std::to_string(image.image_id));
    }
    if (image_id >= kMaxNumImages) Fail(label + ": id out of COLMAP's range");
    if (database.cameras.count(image.camera_id) == 0) {
      Fail(label + ": camera id " + std::to_string(image.camera_id) + " is not among the cameras");
    }
    if (!names.insert(image.name).second) Fail(label + ": another image has the same name");
  }
}

void CheckWritableFeatures(const FeatureDatabase& database, const WriteFailure& Fail) {
  for (const auto& [image_id, keypoints] : database.keypoints) {
    if (database.images.count(image_id) == 0) {
      Fail("keypoints for image id " + std::to_string(image_id) + ", which is not an image");
    }
    const int cols = keypoints.num_cols;
    if ((cols != 2 && cols != 4 && cols != 6) || keypoints.data.size() % cols != 0) {
      Fail("keypoints of " + ImageLabel(database, image_id) + ": " +
           std::to_string(keypoints.data.size()) + " values in " + std::to_string(cols) +
           " columns (must be 2, 4 or 6 and divide the values)");
    }
  }
  for (const auto& [image_id, descriptors] : database.descriptors) {
    if (database.images.count(image_id) == 0) {
      Fail("descriptors for image id " + std::to_string(image_id) + ", which is not an image");
    }
    const int cols = descriptors.num_cols;
    if (cols < 0 || (cols == 0 && !descriptors.data.empty()) ||
        (cols > 0 && descriptors.data.size() % cols != 0)) {
      Fail("descriptors of " + ImageLabel(database, image_id) + ": " +
           std::to_string(descriptors.data.size()) + " values in " + std::to_string(cols) +
           " columns");
    }
  }
}

// The images of `pair_id`, which must be a pair of two known images.
std::pair<uint32_t, uint32_t> CheckWritablePairId(const FeatureDatabase& database, uint64_t pair_id,
                                                  const char* what, const WriteFailure& Fail) {
  const auto [id1, id2] = PairIdToImagePair(pair_id);
  if (id1 >= id2 || ImagePairToPairId(id1, id2) != pair_id || database.images.count(id1) == 0 ||
      database.images.count(id2) == 0) {
    Fail(std::string(what) + " under pair_id " + std::to_string(pair_id) +
         ", which is not a pair of two known images");
  }
  return {id1, id2};
}

void CheckWritableTwoViewGeometry(const FeatureDatabase& database, uint64_t pair_id,
                                  const TwoViewGeometry& geometry, const WriteFailure& Fail) {
  CheckWritablePairId(database, pair_id, "two-view geometry", Fail);
  if (ImagePairToPairId(geometry.image_id1, geometry.image_id2) != pair_id ||
      geometry.image_id1 == geometry.image_id2) {
    Fail("two-view geometry of images (" + std::to_string(geometry.image_id1) + ", " +
         std::to_string(geometry.image_id2) + ") is stored under pair_id " +
         std::to_string(pair_id) + " of another pair");
  }
  const int config = static_cast<int>(geometry.config);
  if (config < 0 || config > static_cast<int>(TwoViewConfig::kCalibratedRig)) {
    Fail("two-view geometry of " + PairLabel(database, geometry.image_id1, geometry.image_id2) +
         ": unknown configuration type " + std::to_string(config));
  }
  CheckMatchIndices(database, "two-view geometry", geometry.image_id1, geometry.image_id2,
                    geometry.inlier_matches, Fail);
  if (!geometry.inlier_ratios.empty() &&
      geometry.inlier_ratios.size() != geometry.inlier_matches.size()) {
    Fail("two-view geometry of " + PairLabel(database, geometry.image_id1, geometry.image_id2) +
         ": " + std::to_string(geometry.inlier_ratios.size()) + " descriptor ratios for " +
         std::to_string(geometry.inlier_matches.size()) + " inlier matches");
  }
}

}  // namespace

void CheckWritable(const FeatureDatabase& database, const std::string& path) {
  const WriteFailure fail{path};
  CheckWritableCamerasAndImages(database, fail);
  CheckWritableFeatures(database, fail);
  for (const auto& [pair_id, matches] : database.matches) {
    const auto [id1, id2] = CheckWritablePairId(database, pair_id, "matches", fail);
    CheckMatchIndices(database, "matches", id1, id2, matches, fail);
  }
  for (const auto& [pair_id, geometry] : database.two_view_geometries) {
    CheckWritableTwoViewGeometry(database, pair_id, geometry, fail);
  }
}

template <typename Matrix>
void BindRowMajor(Statement& statement, int index, const Matrix& matrix) {
  const Eigen::Matrix<double, Matrix::RowsAtCompileTime, Matrix::ColsAtCompileTime, Eigen::RowMajor>
      row_major = matrix;
  statement.BindBlob(index, row_major.data(), row_major.size() * sizeof(double));
}

void WriteImageRows(const FeatureDatabase& database, DatabaseGeneration generation,
                    Connection& db) {
  Statement camera_row(db,
                       "INSERT INTO cameras(camera_id, model, width, height, params, "
                       "prior_focal_length) VALUES(?, ?, ?, ?, ?, ?)");
  for (const auto& [camera_id, camera] : database.cameras) {
    camera_row.BindInt64(1, camera_id);
    camera_row.BindInt64(2, static_cast<int>(camera.model));
    camera_row.BindInt64(3, static_cast<int64_t>(camera.width));
    camera_row.BindInt64(4, static_cast<int64_t>(camera.height));
    camera_row.BindBlob(5, camera.params.data(), camera.params.size() * sizeof(double));
    camera_row.BindInt64(6, camera.has_prior_focal_length ? 1 : 0);
    camera_row.Run();
  }

  // From 3.10 on the priors have a table of their own (written below), without rotations.
  const bool prior_columns = generation == DatabaseGeneration::kColmap38;
  Statement image_row(
      db, prior_columns
              ? "INSERT INTO images(image_id, name, camera_id, prior_qw, prior_qx, prior_qy, "
                "prior_qz, prior_tx, prior_ty, prior_tz) VALUES(?, ?, ?, ?, ?, ?, ?, ?, ?, ?)"
              : "INSERT INTO images(image_id, name, camera_id) VALUES(?, ?, ?)");
  for (const auto& [image_id, image] : database.images) {
    image_row.BindInt64(1, image_id);
    image_row.BindText(2, image.name);
    image_row.BindInt64(3, image.camera_id);
    // Unbound parameters are NULL: an absent prior.
    if (prior_columns && image.prior_rotation) {
      const Eigen::Quaterniond& q = *image.prior_rotation;
      image_row.BindDouble(4, q.w());
      image_row.BindDouble(5, q.x());
      image_row.BindDouble(6, q.y());
      image_row.BindDouble(7, q.z());
    }
    if (prior_columns && image.prior_translation) {
      for (int i = 0; i < 3; ++i) image_row.BindDouble(8 + i, (*image.prior_translation)[i]);
    }
    image_row.Run();
  }

  Statement keypoint_row(db,
                         "INSERT INTO keypoints(image_id, rows, cols, data) VALUES(?, ?, ?, ?)");
  for (const auto& [image_id, keypoints] : database.keypoints) {
    keypoint_row.BindInt64(1, image_id);
    keypoint_row.BindInt64(2, static_cast<int64_t>(keypoints.size()));
    keypoint_row.BindInt64(3, keypoints.num_cols);
    keypoint_row.BindBlob(4, keypoints.data.data(), keypoints.data.size() * sizeof(float));
    keypoint_row.Run();
  }

  // COLMAP 4 types its descriptors (FeatureExtractorType): 0 SIFT, -1 undefined (ramap's ORB),
  // and matches only descriptors of one type.
  const bool typed = generation == DatabaseGeneration::kColmap4;
  Statement descriptor_row(
      db, typed ? "INSERT INTO descriptors(image_id, rows, cols, data, type) VALUES(?, ?, ?, ?, ?)"
                : "INSERT INTO descriptors(image_id, rows, cols, data) VALUES(?, ?, ?, ?)");
  for (const auto& [image_id, descriptors] : database.descriptors) {
    descriptor_row.BindInt64(1, image_id);
    descriptor_row.BindInt64(2, static_cast<int64_t>(descriptors.size()));
    descriptor_row.BindInt64(3, descriptors.num_cols);
    descriptor_row.BindBlob(4, descriptors.data.data(), descriptors.data.size());
    if (typed) descriptor_row.BindInt64(5, descriptors.num_cols == 128 ? 0 : -1);
    descriptor_row.Run();
  }
  WriteDatabasePosePriors(database, generation, db);
  if (generation == DatabaseGeneration::kColmap4) WriteDatabaseRigsAndFrames(database, db);
}

// COLMAP 4 stores an unknown F, E, H or relative pose as NULL, where older versions stored zeros
// and the identity (which COLMAP 4 turns into NULL when it upgrades such a database).
template <typename Matrix>
void BindMatrixOrNull(Statement& statement, int index, const Matrix& matrix, bool null_if_zero) {
  if (null_if_zero && matrix.isZero(0)) {
    statement.BindNull(index);
  } else {
    BindRowMajor(statement, index, matrix);
  }
}

void WriteMatchRows(const FeatureDatabase& database, DatabaseGeneration generation,
                    Connection& db) {
  const bool null_if_unknown = generation == DatabaseGeneration::kColmap4;
  Statement match_row(db, "INSERT INTO matches(pair_id, rows, cols, data) VALUES(?, ?, ?, ?)");
  for (const auto& [pair_id, matches] : database.matches) {
    match_row.BindInt64(1, static_cast<int64_t>(pair_id));
    match_row.BindInt64(2, static_cast<int64_t>(matches.size()));
    match_row.BindInt64(3, 2);
    match_row.BindBlob(4, matches.data(), matches.size() * sizeof(FeatureMatch));
    match_row.Run();
  }

  Statement geometry_row(db,
                         "INSERT INTO two_view_geometries(pair_id, rows, cols, data, config, F, E, "
                         "H, qvec, tvec) VALUES(?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  for (const auto& [pair_id, given] : database.two_view_geometries) {
    // COLMAP keeps every pair as (smaller id, larger id); see the header.
    const TwoViewGeometry geometry = ShouldSwapImagePair(given.image_id1, given.image_id2)
                                         ? InvertTwoViewGeometry(given)
                                         : given;
    geometry_row.BindInt64(1, static_cast<int64_t>(pair_id));
    geometry_row.BindInt64(2, static_cast<int64_t>(geometry.inlier_matches.size()));
    geometry_row.BindInt64(3, 2);
    geometry_row.BindBlob(4, geometry.inlier_matches.data(),
                          geometry.inlier_matches.size() * sizeof(FeatureMatch));
    geometry_row.BindInt64(5, static_cast<int>(geometry.config));
    BindMatrixOrNull(geometry_row, 6, geometry.F, null_if_unknown);
    BindMatrixOrNull(geometry_row, 7, geometry.E, null_if_unknown);
    BindMatrixOrNull(geometry_row, 8, geometry.H, null_if_unknown);
    const Eigen::Quaterniond& q = geometry.cam2_from_cam1.rotation;
    const bool unknown_pose = q.coeffs() == Eigen::Quaterniond::Identity().coeffs() &&
                              geometry.cam2_from_cam1.translation.isZero(0);
    if (!(null_if_unknown && unknown_pose)) {
      const Eigen::Vector4d qvec(q.w(), q.x(), q.y(), q.z());
      geometry_row.BindBlob(9, qvec.data(), 4 * sizeof(double));
      geometry_row.BindBlob(10, geometry.cam2_from_cam1.translation.data(), 3 * sizeof(double));
    }
    geometry_row.Run();
  }

  const bool any_ratios =
      std::any_of(database.two_view_geometries.begin(), database.two_view_geometries.end(),
                  [](const auto& entry) { return !entry.second.inlier_ratios.empty(); });
  if (!any_ratios) return;
  db.Execute(std::string("CREATE TABLE IF NOT EXISTS ") + kMatchConfidenceTable +
             " (pair_id INTEGER PRIMARY KEY NOT NULL, rows INTEGER NOT NULL, data BLOB)");
  Statement ratio_row(db, std::string("INSERT INTO ") + kMatchConfidenceTable +
                              "(pair_id, rows, data) VALUES(?, ?, ?)");
  for (const auto& [pair_id, geometry] : database.two_view_geometries) {
    if (geometry.inlier_ratios.empty()) continue;
    // Inverting a geometry keeps the order of its matches, so the ratios need no reordering.
    ratio_row.BindInt64(1, static_cast<int64_t>(pair_id));
    ratio_row.BindInt64(2, static_cast<int64_t>(geometry.inlier_ratios.size()));
    ratio_row.BindBlob(3, geometry.inlier_ratios.data(),
                       geometry.inlier_ratios.size() * sizeof(float));
    ratio_row.Run();
  }
}

}  // namespace

namespace {

// A database path names a file: missing or a folder is said before SQLite is asked.
void CheckDatabaseFile(const std::string& path) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) throw InputError(path, "no such file (expected a COLMAP database)");
  if (fs::is_directory(status)) {
    throw InputError(path, "is a folder; expected a COLMAP database file");
  }
}

}  // namespace

FeatureDatabase ReadColmapDatabase(const std::string& path, const DatabaseReadOptions& options) {
  CheckDatabaseFile(path);
  return Reader(path, options).Read();
}

DatabaseGeneration ReadDatabaseGeneration(const std::string& path) {
  CheckDatabaseFile(path);
  Connection db(path, Connection::OpenExisting(), path);
  db.SetQueryOnly();
  return DetectDatabaseLayout(db).generation;
}

std::vector<std::string> ReadDatabaseImageNames(const std::string& path) {
  DatabaseReadOptions read_options;
  read_options.read_matches = false;
  std::vector<std::string> names;
  for (const auto& [id, image] : ReadColmapDatabase(path, read_options).images) {
    names.push_back(image.name);
  }
  std::sort(names.begin(), names.end());
  return names;
}

void WriteColmapDatabase(const FeatureDatabase& database, const std::string& path,
                         DatabaseGeneration generation) {
  CheckWritable(database, path);
  StagedPath staged(path);
  {
    Connection db(staged.path(), Connection::Create(), path);
    // The staged file is thrown away on any failure, so durability while writing is not needed.
    db.Execute("PRAGMA synchronous = OFF; PRAGMA journal_mode = MEMORY;");
    db.Execute("BEGIN TRANSACTION");
    for (const std::string& statement : SchemaStatements(generation)) db.Execute(statement);
    db.Execute("PRAGMA user_version = " + std::to_string(SchemaUserVersion(generation)));
    WriteImageRows(database, generation, db);
    WriteMatchRows(database, generation, db);
    db.Execute("COMMIT");
    // COLMAP keeps its databases in WAL mode (a setting stored in the file); closing the
    // connection checkpoints and removes the -wal file, so only the database is renamed.
    db.Execute("PRAGMA journal_mode = WAL");
  }
  staged.Commit();
}

void WriteColmapDatabaseMatches(const FeatureDatabase& database, const std::string& path) {
  CheckWritable(database, path);
  Connection db(path, Connection::OpenExisting(), path);
  db.Execute("BEGIN IMMEDIATE TRANSACTION");
  // The images must be the file's own: pairs are stored by image id.
  std::map<int64_t, std::string> stored;
  {
    Statement row(db, "SELECT image_id, name FROM images");
    while (row.Step()) stored[row.ColumnInt64(0)] = row.ColumnText(1);
  }
  for (const auto& [image_id, image] : database.images) {
    const auto found = stored.find(image_id);
    if (found == stored.end() || found->second != image.name) {
      throw InputError(path, "cannot write the matches: image id " + std::to_string(image_id) +
                                 " (" + image.name + ") is not that image in the database");
    }
  }
  // The file keeps its generation: its geometries are stored by its conventions.
  const DatabaseGeneration generation = DetectDatabaseLayout(db).generation;
  db.Execute("DELETE FROM matches; DELETE FROM two_view_geometries;");
  db.Execute(std::string("DROP TABLE IF EXISTS ") + kMatchConfidenceTable);
  WriteMatchRows(database, generation, db);
  // Nothing is changed unless everything is: an exception before this line rolls back when the
  // connection closes.
  db.Execute("COMMIT");
}

DatabaseCounts CountDatabase(const FeatureDatabase& database) {
  DatabaseCounts counts;
  for (const auto& [image_id, keypoints] : database.keypoints)
    counts.num_keypoints += keypoints.size();
  for (const auto& [image_id, descriptors] : database.descriptors)
    counts.num_descriptors += descriptors.size();
  for (const auto& [pair_id, matches] : database.matches) {
    counts.num_pairs_with_matches += matches.empty() ? 0 : 1;
    counts.num_matches += matches.size();
  }
  for (const auto& [pair_id, geometry] : database.two_view_geometries) {
    counts.num_pairs_with_ratios += geometry.inlier_ratios.empty() ? 0 : 1;
    if (geometry.inlier_matches.empty()) continue;
    ++counts.num_verified_pairs;
    counts.num_inliers += geometry.inlier_matches.size();
    ++counts.verified_pairs_by_config[geometry.config];
  }
  for (const auto& [image_id, image] : database.images) {
    counts.num_pose_priors += image.prior_translation ? 1 : 0;
    counts.num_rotation_priors += image.prior_rotation ? 1 : 0;
  }
  return counts;
}

}  // namespace ramap
