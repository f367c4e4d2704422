// `ramap mapper`: a COLMAP database in, COLMAP models out, by motion averaging.
#include <iostream>

#include "mapper_report.h"
#include "options.h"
#include "ramap/jobs/mapper_job.h"
#include "ramap/mapper/mapper_options.h"

namespace ramap::cli {
namespace {

struct MapperCommand {
  MapperJob job;
  int log_level = 1;
};

const OptionTable<MapperCommand>& MapperCommandTable() {
  static const OptionTable<MapperCommand> table = [] {
    OptionTable<MapperCommand> t;
    t.push_back(Required(PathOption<MapperCommand>(
        "database_path", [](auto& o) -> auto& { return o.job.database_path; },
        "COLMAP database (features and verified matches)")));
    t.push_back(PathOption<MapperCommand>(
        "image_path", [](auto& o) -> auto& { return o.job.image_path; },
        "folder of the images (optional): points get their colours from it"));
    t.push_back(Required(PathOption<MapperCommand>(
        "output_path", [](auto& o) -> auto& { return o.job.output_path; },
        "folder for the models 0, 1, ... and summary.json")));
    t.push_back(
        ModelFormatOption<MapperCommand>([](auto& o) -> auto& { return o.job.output_format; }));
    t.push_back(LogLevelOption<MapperCommand>([](auto& o) -> auto& { return o.log_level; }));
    AppendOptions(
        MapperOptionTable(), [](auto& o) -> auto& { return o.job.options; }, &t);
    return t;
  }();
  return table;
}

}  // namespace

std::string MapperOptionsMarkdown() {
  return OptionTableMarkdown(MapperCommandTable(), MapperCommand());
}

int RunMapper(int argc, char** argv) {
  CLI::App app("Camera poses and points from a COLMAP database by motion averaging",
               "ramap mapper");
  MapperCommand command;
  if (const auto code = ParseCommandLine(app, MapperCommandTable(), &command, argc, argv))
    return *code;
  const MapperResult result =
      RunMapperJob(command.job, ProgressStream(command.log_level), &std::cerr);
  PrintMapperSummary(result.summary, command.job.output_path, std::cout);
  return 0;
}

}  // namespace ramap::cli
