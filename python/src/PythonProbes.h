#pragma once
// tmdem.read_probes(path): the [[probe]] readings of a result file (/probes,
// coupling/output/ResultProbes.h) by probe name, each a dict of NumPy arrays over the complete
// frames: time_s, count, mean_K, min_K, max_K. Count 0: no particle inside that frame, its
// temperatures then 0. A file without probes gives an empty dict.
#include <string>

#include <pybind11/pybind11.h>

namespace tmdem::python {

pybind11::dict read_probes(const std::string& path);

}  // namespace tmdem::python
