#include "ramap/io/geo_export.h"

#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>

#include "ramap/util/error.h"
#include "ramap/util/staged_output.h"

namespace ramap {

void WriteGeoOrigin(const GeodeticPoint& origin, const std::string& path) {
  WriteFileAtomically(path, [&](std::ostream& out) {
    out << "# Origin of this model's east-north-up frame (metres), WGS84:\n"
           "# LATITUDE_DEG LONGITUDE_DEG ALTITUDE_M (above the ellipsoid)\n"
        << std::setprecision(12) << origin.latitude_deg << " " << origin.longitude_deg << " "
        << origin.altitude_m << "\n";
  });
}

GeodeticPoint ReadGeoOrigin(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw InputError(path, "cannot open the geodetic origin file");
  std::string line;
  while (std::getline(file, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream in(line);
    GeodeticPoint origin;
    std::string rest;
    if (!(in >> origin.latitude_deg >> origin.longitude_deg >> origin.altitude_m) || (in >> rest) ||
        !IsValidGeodeticPoint(origin)) {
      throw InputError(path, "expected 'LATITUDE LONGITUDE ALTITUDE', found '" + line + "'");
    }
    return origin;
  }
  throw InputError(path, "no origin line");
}

void WriteCamerasGeoJson(const Reconstruction& reconstruction, const LocalEnuFrame& frame,
                         const std::string& path) {
  nlohmann::json features = nlohmann::json::array();
  for (const auto& [id, image] : reconstruction.images) {
    const GeodeticPoint point = frame.ToGeodetic(CameraCenter(image.cam_from_world));
    features.push_back(
        {{"type", "Feature"},
         {"geometry",
          {{"type", "Point"},
           {"coordinates", {point.longitude_deg, point.latitude_deg, point.altitude_m}}}},
         {"properties", {{"name", image.name}, {"image_id", id}}}});
  }
  const nlohmann::json collection = {{"type", "FeatureCollection"}, {"features", features}};
  WriteFileAtomically(path, [&](std::ostream& out) {
    // Nine decimals of a degree are 0.1 mm.
    out << std::setprecision(15) << collection.dump(1) << "\n";
  });
}

void WriteGeoreference(const Reconstruction& reconstruction, const GeodeticPoint& origin,
                       const std::string& model_folder) {
  WriteGeoOrigin(origin, model_folder + "/geo_origin.txt");
  WriteCamerasGeoJson(reconstruction, LocalEnuFrame(origin), model_folder + "/cameras.geojson");
}

}  // namespace ramap
