#include "PythonProbes.h"

#include <pybind11/numpy.h>

#include "coupling/output/ResultProbes.h"

namespace py = pybind11;

namespace tmdem::python {

namespace {

// Column p of a [F, P] row-major series.
template <typename T>
py::array_t<T> column(const std::vector<T>& values, std::size_t frames, std::size_t probes,
                      std::size_t p) {
  py::array_t<T> out(static_cast<py::ssize_t>(frames));
  for (std::size_t f = 0; f < frames; ++f) out.mutable_at(f) = values[f * probes + p];
  return out;
}

}  // namespace

py::dict read_probes(const std::string& path) {
  bool has_probes = false;
  const coupling::ProbeSeries s = coupling::read_probe_series(path, has_probes);
  py::dict out;
  const std::size_t frames = s.time_s.size(), probes = s.names.size();
  for (std::size_t p = 0; p < probes; ++p) {
    py::dict probe;
    py::array_t<double> time(static_cast<py::ssize_t>(frames));
    std::copy(s.time_s.begin(), s.time_s.end(), time.mutable_data());
    probe["time_s"] = time;
    probe["count"] = column(s.count, frames, probes, p);
    probe["mean_K"] = column(s.mean_K, frames, probes, p);
    probe["min_K"] = column(s.min_K, frames, probes, p);
    probe["max_K"] = column(s.max_K, frames, probes, p);
    out[py::str(s.names[p])] = probe;
  }
  return out;
}

}  // namespace tmdem::python
