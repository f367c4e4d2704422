// `ramap database_converter --database_path IN --output_path OUT --Database.generation 3.8|3.10|4`:
// a COLMAP database of any generation rewritten as another, everything kept that the target holds
// (a 4.x database made by pycolmap or hloc, for COLMAP 3.8; or the other way round).
#include <iostream>

#include "options.h"
#include "ramap/io/colmap_database.h"
#include "ramap/io/colmap_database_schema.h"
#include "ramap/util/output_policy.h"

namespace ramap::cli {

int RunDatabaseConverter(int argc, char** argv) {
  CLI::App app("Rewrite a COLMAP database (3.8 to 4.x) as another generation",
               "ramap database_converter");
  std::string database_path, output_path, generation_name = "3.8";
  app.add_option("--database_path", database_path, "COLMAP database to read")->required();
  app.add_option("--output_path", output_path, "the new database (must not exist)")->required();
  app.add_option("--Database.generation", generation_name,
                 "3.8 (read by every COLMAP) | 3.10 (3.10-3.11) | 4 (3.12-4.x)")
      ->capture_default_str();
  if (const std::optional<int> code = ParseOptions(app, argc, argv)) return *code;
  const DatabaseGeneration generation =
      DatabaseGenerationFromName(generation_name, "--Database.generation");
  CheckNewDatabasePath("--output_path", output_path, {database_path});
  DatabaseReadOptions read_options;
  read_options.read_descriptors = true;
  const FeatureDatabase database = ReadColmapDatabase(database_path, read_options);
  WriteColmapDatabase(database, output_path, generation);
  std::cout << "Wrote " << output_path << " (" << DatabaseGenerationLabel(generation) << ", from "
            << DatabaseGenerationLabel(database.generation) << ")\n";
  return 0;
}

}  // namespace ramap::cli
