// `ramap database_converter --database_path IN --output_path OUT --Database.generation 3.8|3.10|4`:
// a COLMAP database of any generation rewritten as another, everything kept that the target holds
// (a 4.x database made by pycolmap or hloc, for COLMAP 3.8; or the other way round).
#include <iostream>

#include "options.h"
#include "ramap/io/colmap_database.h"
#include "ramap/io/colmap_database_schema.h"
#include "ramap/util/output_policy.h"

namespace ramap::cli {
namespace {

struct ConverterCommand {
  std::string database_path, output_path;
  DatabaseGeneration generation = DatabaseGeneration::kColmap38;
};

const OptionTable<ConverterCommand>& ConverterCommandTable() {
  static const OptionTable<ConverterCommand> table = {
      Required(PathOption<ConverterCommand>(
          "database_path", [](auto& o) -> auto& { return o.database_path; },
          "COLMAP database to read")),
      Required(PathOption<ConverterCommand>(
          "output_path", [](auto& o) -> auto& { return o.output_path; },
          "the new database (must not exist)")),
      DatabaseGenerationOption<ConverterCommand>([](auto& o) -> auto& { return o.generation; })};
  return table;
}

}  // namespace

std::string DatabaseConverterOptionsMarkdown() {
  return OptionTableMarkdown(ConverterCommandTable(), ConverterCommand());
}

int RunDatabaseConverter(int argc, char** argv) {
  CLI::App app("Rewrite a COLMAP database (3.8 to 4.x) as another generation",
               "ramap database_converter");
  ConverterCommand command;
  if (const auto code = ParseCommandLine(app, ConverterCommandTable(), &command, argc, argv))
    return *code;
  const std::string& database_path = command.database_path;
  const std::string& output_path = command.output_path;
  const DatabaseGeneration generation = command.generation;
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
