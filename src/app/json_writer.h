// The JSON writer lives in the pipeline (the Python module writes the same reports): this name stays
// for the CLI's files.
#pragma once

#include "pipeline/json_writer.h"

namespace polarview::cli {
using polarview::JsonWriter;
}  // namespace polarview::cli
