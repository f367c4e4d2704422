#include "ramap/io/pose_prior_file.h"

#include <fstream>
#include <iomanip>
#include <sstream>

#include "ramap/util/error.h"
#include "ramap/util/staged_output.h"

namespace ramap {
namespace {

// strtod accepts "nan" and "inf", which must reach LocalizePriors as values to report.
bool ParseNumber(const std::string& text, double* value) {
  std::size_t used = 0;
  try {
    *value = std::stod(text, &used);
  } catch (const std::exception&) {
    return false;
  }
  return used == text.size();
}

}  // namespace

PriorCoordinates PriorCoordinatesFromName(const std::string& name, const std::string& option) {
  if (name == "wgs84") return PriorCoordinates::kWgs84;
  if (name == "enu") return PriorCoordinates::kEnu;
  if (name == "ecef") return PriorCoordinates::kEcef;
  if (name == "xyz") return PriorCoordinates::kXyz;
  throw InputError(option, "'" + name + "' is not wgs84, enu, ecef or xyz");
}

const char* PriorCoordinatesName(PriorCoordinates coordinates) {
  switch (coordinates) {
    case PriorCoordinates::kWgs84:
      return "wgs84";
    case PriorCoordinates::kEnu:
      return "enu";
    case PriorCoordinates::kEcef:
      return "ecef";
    case PriorCoordinates::kXyz:
      return "xyz";
  }
  return "?";
}

std::vector<PriorRecord> ReadPriorFile(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw InputError(path, "cannot open the pose prior file");
  std::vector<PriorRecord> records;
  std::string line;
  for (int line_number = 1; std::getline(file, line); ++line_number) {
    std::istringstream in(line);
    std::vector<std::string> fields;
    for (std::string field; in >> field;) fields.push_back(field);
    if (fields.empty() || fields[0][0] == '#') continue;
    const std::string where = path + ":" + std::to_string(line_number);
    if (fields.size() != 4 && fields.size() != 7) {
      throw InputError(where, "expected 'NAME V1 V2 V3' or 'NAME V1 V2 V3 S1 S2 S3', found " +
                                  std::to_string(fields.size()) + " fields");
    }
    PriorRecord record;
    record.image_name = fields[0];
    record.where = where;
    double numbers[6];
    for (size_t k = 1; k < fields.size(); ++k) {
      if (!ParseNumber(fields[k], &numbers[k - 1])) {
        throw InputError(where,
                         "field " + std::to_string(k + 1) + " '" + fields[k] + "' is not a number");
      }
    }
    record.value = Eigen::Vector3d(numbers[0], numbers[1], numbers[2]);
    if (fields.size() == 7) record.std_dev_m = Eigen::Vector3d(numbers[3], numbers[4], numbers[5]);
    records.push_back(record);
  }
  if (file.bad()) throw InputError(path, "read error");
  return records;
}

void WritePriorFile(const std::vector<PriorRecord>& records, const std::string& path) {
  WriteFileAtomically(path, [&](std::ostream& out) {
    out << "# NAME V1 V2 V3 [S1 S2 S3]\n" << std::setprecision(12);
    for (const PriorRecord& record : records) {
      out << record.image_name << " " << record.value.x() << " " << record.value.y() << " "
          << record.value.z();
      if (record.std_dev_m) {
        out << " " << record.std_dev_m->x() << " " << record.std_dev_m->y() << " "
            << record.std_dev_m->z();
      }
      out << "\n";
    }
  });
}

}  // namespace ramap
