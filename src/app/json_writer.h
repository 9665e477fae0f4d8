// The JSON writer lives in the pipeline (the reports print through it): this name stays for the
// CLI's files.
#pragma once

#include "pipeline/json_writer.h"

namespace polarview::cli {
using polarview::JsonWriter;
}  // namespace polarview::cli
