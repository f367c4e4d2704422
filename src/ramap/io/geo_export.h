// Files written beside a model aligned to its priors (its frame east-north-up about a WGS84
// origin):
//   geo_origin.txt   the origin, "LATITUDE LONGITUDE ALTITUDE", so the model maps back to WGS84;
//   cameras.geojson  one GeoJSON point (RFC 7946: longitude, latitude, altitude) per camera centre,
//                    with the image name, for any map viewer (geojson.io, QGIS, Google Earth).
// COLMAP ignores files it does not know in a model folder, so the model still opens in its GUI.
#pragma once

#include <string>

#include "ramap/geometry/geodetic.h"
#include "ramap/scene/reconstruction.h"

namespace ramap {

void WriteGeoOrigin(const GeodeticPoint& origin, const std::string& path);
// Reads what WriteGeoOrigin wrote; throws InputError naming the file when malformed.
GeodeticPoint ReadGeoOrigin(const std::string& path);

void WriteCamerasGeoJson(const Reconstruction& reconstruction, const LocalEnuFrame& frame,
                         const std::string& path);

// Both files into `model_folder`.
void WriteGeoreference(const Reconstruction& reconstruction, const GeodeticPoint& origin,
                       const std::string& model_folder);

}  // namespace ramap
