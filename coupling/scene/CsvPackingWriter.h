#pragma once
// A packing as CSV in the columns CsvPackingReader reads back (what `tmdem export` writes):
//   x,y,z,radius,material,temperature    (m, m, m, m, a [[material]] name, K)
// plus fixed, fixed_temperature, heat_source when any row has them. Numbers are written as the
// shortest text that reads back as the same double, so export then import is exact.
#include <string>

#include "coupling/scene/PackingFile.h"

namespace tmdem::coupling {

std::string packing_csv(const Packing& packing);

}  // namespace tmdem::coupling
