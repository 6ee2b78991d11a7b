#pragma once
// tmdem.Result: a result file (contract section 3) read whole into NumPy arrays through the
// project's HDF5 helpers (no h5py). A file of a run still going is read up to its last complete
// frame: frames datasets are cut to len(/frames/time), contacts to contact_offset[F].
#include <string>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

namespace tmdem::python {

struct PythonResult {
  explicit PythonResult(const std::string& path);

  // Frame f's contacts as a dict of array views: pair, normal_force, tangential_force,
  // conductance, heat_flow. IndexError outside 0 .. frames - 1 (negative counts from the end).
  pybind11::dict contacts(long frame) const;
  long frames() const { return static_cast<long>(time.shape(0)); }

  std::string path, format, status, scene;
  bool contacts_stored = true;
  pybind11::array_t<double> radius, mass, heat_capacity;         // [N]  m, kg, J/K
  pybind11::array_t<std::int64_t> material;                       // [N]
  pybind11::array_t<double> time, thermal_energy, boundary_heat;  // [F]  s, J, J
  pybind11::array_t<double> position, velocity;                   // [F, N, 3]  m, m/s
  pybind11::array_t<double> temperature;                          // [F, N]  K
  pybind11::array_t<std::int64_t> contact_offset;                 // [F + 1]
  pybind11::array_t<std::int64_t> pair;                           // [C, 2]
  pybind11::array_t<double> normal_force, conductance;            // [C]  N, W/K
  pybind11::array_t<double> heat_flow;                            // [C]  W, from i to j
  pybind11::array_t<double> tangential_force;                     // [C, 3]  N
};

}  // namespace tmdem::python
