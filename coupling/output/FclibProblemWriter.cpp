#include "coupling/output/FclibProblemWriter.h"

#include <hdf5.h>
// fclib.h declares C functions without extern "C".
extern "C" {
#include <fclib.h>
}

#include <dlfcn.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "coupling/output/Hdf5ErrorSilence.h"
#include "coupling/output/Hdf5Handle.h"
#include "coupling/output/Hdf5Io.h"
#include "coupling/output/OutputError.h"

namespace tmdem::coupling {

namespace {

// libfclib is loaded when a problem is written, not linked: linked into tmdem, it changed the
// order in which the HDF5 libraries shut down at exit, and a run whose result file could not be
// written (a full disk) then crashed there instead of ending with exit code 4.
struct Fclib {
  decltype(&fclib_write_local) write_local = nullptr;
  decltype(&fclib_write_solution) write_solution = nullptr;
  decltype(&fclib_write_guesses) write_guesses = nullptr;
};

const Fclib& fclib() {
  static const Fclib loaded = [] {
    Fclib f;
    void* library = dlopen("libfclib.so.0", RTLD_NOW | RTLD_LOCAL);
    if (!library) library = dlopen("libfclib.so", RTLD_NOW | RTLD_LOCAL);
    if (!library)
      throw OutputError(std::string("cannot load libfclib (install Debian's libfclib-dev, "
                                    "or run scripts/setup.sh): ") + dlerror());
    f.write_local = reinterpret_cast<decltype(f.write_local)>(dlsym(library, "fclib_write_local"));
    f.write_solution =
        reinterpret_cast<decltype(f.write_solution)>(dlsym(library, "fclib_write_solution"));
    f.write_guesses =
        reinterpret_cast<decltype(f.write_guesses)>(dlsym(library, "fclib_write_guesses"));
    if (!f.write_local || !f.write_solution || !f.write_guesses)
      throw OutputError("libfclib lacks fclib_write_local, fclib_write_solution or "
                        "fclib_write_guesses");
    return f;
  }();
  return loaded;
}

void check_sizes(const FclibLocalProblem& p) {
  const std::size_t m = p.contacts * std::size_t(p.spacedim);
  const bool ok = (p.spacedim == 2 || p.spacedim == 3) && p.column_start.size() == m + 1 &&
                  p.row.size() == p.value.size() &&
                  std::size_t(p.column_start.back()) == p.row.size() && p.q.size() == m &&
                  p.r.size() == m && p.u.size() == m && p.mu.size() == p.contacts &&
                  p.body_i.size() == p.contacts && p.body_j.size() == p.contacts &&
                  p.normal.size() == p.contacts && p.tangent1.size() == p.contacts &&
                  p.tangent2.size() == p.contacts;
  if (!ok) throw std::logic_error("write_fclib_local_problem: inconsistent problem sizes");
}

// Written with HDF5's C API, as every other tmdem file: the C++ library, once linked, closes
// what is left open at exit, and after a failed write (a full disk) that crashed the program.
void write_dataset(hid_t group, const char* name, hid_t type, const void* data, int rank,
                   const hsize_t* dims) {
  const Hdf5Handle space(rank == 0 ? H5Screate(H5S_SCALAR) : H5Screate_simple(rank, dims, nullptr),
                         H5Sclose);
  hdf5::check_id(space.get(), std::string("dataspace of /tmdem/") + name);
  const Hdf5Handle set(H5Dcreate2(group, name, type, space.get(), H5P_DEFAULT, H5P_DEFAULT,
                                  H5P_DEFAULT), H5Dclose);
  hdf5::check_id(set.get(), std::string("/tmdem/") + name);
  if (rank == 0 || dims[0] > 0)
    hdf5::check_ok(H5Dwrite(set.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data),
                   std::string("writing /tmdem/") + name);
}

template <class T>
void write_scalar(hid_t group, const char* name, const T& value, hid_t type) {
  write_dataset(group, name, type, &value, 0, nullptr);
}

template <class T>
void write_array(hid_t group, const char* name, const T* data, hsize_t rows, hsize_t columns,
                 hid_t type) {
  const hsize_t dims[2] = {rows, columns};
  write_dataset(group, name, type, data, columns == 1 ? 1 : 2, dims);
}

// The /tmdem group (FclibProblemWriter.h), into the file FCLIB has written.
void write_tmdem_group(const FclibLocalProblem& p, const std::string& path) {
  const Hdf5Handle file = hdf5::open_file(path, true, false);
  const Hdf5Handle group = hdf5::create_group(file.get(), "/tmdem");
  const hid_t g = group.get();
  const hsize_t n = p.contacts;
  write_array(g, "body_i", p.body_i.data(), n, 1, H5T_NATIVE_INT32);
  write_array(g, "body_j", p.body_j.data(), n, 1, H5T_NATIVE_INT32);
  write_array(g, "normal", p.normal.data()->data(), n, 3, H5T_NATIVE_DOUBLE);
  write_array(g, "tangent1", p.tangent1.data()->data(), n, 3, H5T_NATIVE_DOUBLE);
  write_array(g, "tangent2", p.tangent2.data()->data(), n, 3, H5T_NATIVE_DOUBLE);
  write_array(g, "gravity_impulse", p.gravity_impulse.data(), 3, 1, H5T_NATIVE_DOUBLE);
  write_scalar(g, "time_step", p.time_step_s, H5T_NATIVE_DOUBLE);
  write_scalar(g, "step", p.step, H5T_NATIVE_INT64);
  write_scalar(g, "dimension", p.dimension, H5T_NATIVE_INT);
  write_scalar(g, "solver_tolerance", p.solver_tolerance, H5T_NATIVE_DOUBLE);
  write_scalar(g, "solver_residual", p.solver_residual, H5T_NATIVE_DOUBLE);
  write_scalar(g, "siconos_residual", p.siconos_residual, H5T_NATIVE_DOUBLE);
  write_scalar(g, "solver_seconds", p.solver_seconds, H5T_NATIVE_DOUBLE);
  write_scalar(g, "solver_iterations", p.solver_iterations, H5T_NATIVE_INT64);
  write_scalar(g, "omitted_contacts", p.omitted_contacts, H5T_NATIVE_INT64);
}

void write_all(const FclibLocalProblem& p, const std::string& path) {
  const int m = int(p.contacts) * p.spacedim;
  // FCLIB's structs take non-const pointers; it only reads through them.
  std::vector<int> column_start = p.column_start, row = p.row;
  std::vector<double> value = p.value, q = p.q, mu = p.mu, r = p.r, u = p.u;
  std::string title = p.title, description = p.description, math_info = p.math_info;
  std::string comment = "Delassus operator W = H^T M^-1 H, 1/kg";

  fclib_matrix_info matrix_info{comment.data(), 0.0, 0.0, 0};
  fclib_matrix W{};
  W.nzmax = int(value.size());
  W.m = m;
  W.n = m;
  W.p = column_start.data();
  W.i = row.data();
  W.x = value.data();
  W.nz = -1;  // compressed columns
  W.info = &matrix_info;
  fclib_info info{title.data(), description.data(), math_info.data()};
  fclib_local local{};
  local.W = &W;
  local.mu = mu.data();
  local.q = q.data();
  local.spacedim = p.spacedim;
  local.info = &info;
  // FCLIB adds to an existing file and refuses one that holds a local problem already.
  std::error_code ec;
  std::filesystem::remove(path, ec);
  if (!fclib().write_local(&local, path.c_str()))
    throw OutputError("cannot write FCLIB problem '" + path + "' (fclib_write_local failed)");
  fclib_solution solution{nullptr, u.data(), r.data(), nullptr};
  if (!fclib().write_solution(&solution, path.c_str()))
    throw OutputError("cannot write the solution into '" + path + "' (fclib_write_solution failed)");
  if (!fclib().write_guesses(1, &solution, path.c_str()))
    throw OutputError("cannot write the guess into '" + path + "' (fclib_write_guesses failed)");
  try {
    const Hdf5ErrorSilence silence;
    write_tmdem_group(p, path);
  } catch (const Hdf5Failure& e) {
    throw OutputError("cannot write the /tmdem group into '" + path + "': " + e.what());
  }
}

}  // namespace

void write_fclib_local_problem(const FclibLocalProblem& problem, const std::string& path) {
  check_sizes(problem);
  try {
    write_all(problem, path);
  } catch (...) {
    std::error_code ec;
    std::filesystem::remove(path, ec);
    throw;
  }
}

}  // namespace tmdem::coupling
