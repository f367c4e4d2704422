#include "mapper_options.h"

#include "options.h"
#include "ramap/pipeline/mapper_option_table.h"

namespace ramap::cli {

void AddMapperOptions(CLI::App& app, MapperOptions* options) {
  AddOptionTable(app, MapperOptionTable(), options);
}

}  // namespace ramap::cli
