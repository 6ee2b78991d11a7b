#pragma once
// Particles from a CSV file: a header line of column names (PackingColumns.h), then one
// particle per line, comma-separated. Blank lines and lines starting with '#' are skipped.
// This is what `tmdem export` writes (CsvPackingWriter.h).
#include <string>
#include <string_view>

#include "coupling/scene/PackingFile.h"

namespace tmdem::coupling {

// file: the name used in messages ("FILE:LINE:COLUMN: ...").
Packing read_csv_packing(std::string_view text, const std::string& file,
                         const std::string& temperature_column, bool z_required);

}  // namespace tmdem::coupling
