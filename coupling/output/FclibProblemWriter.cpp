#include "coupling/output/FclibProblemWriter.h"

#include <H5Cpp.h>
// fclib.h declares C functions without extern "C".
extern "C" {
#include <fclib.h>
}

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "coupling/output/Hdf5ErrorSilence.h"
#include "coupling/output/OutputError.h"

namespace tmdem::coupling {

namespace {

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

template <class T>
void write_scalar(H5::Group& group, const char* name, const T& value, const H5::PredType& type) {
  const H5::DataSet set = group.createDataSet(name, type, H5::DataSpace());
  set.write(&value, type);
}

template <class T>
void write_array(H5::Group& group, const char* name, const T* data, hsize_t rows, hsize_t columns,
                 const H5::PredType& type) {
  const hsize_t dims[2] = {rows, columns};
  const H5::DataSpace space(columns == 1 ? 1 : 2, dims);
  const H5::DataSet set = group.createDataSet(name, type, space);
  if (rows > 0) set.write(data, type);
}

// The /tmdem group (FclibProblemWriter.h), into the file FCLIB has written.
void write_tmdem_group(const FclibLocalProblem& p, const std::string& path) {
  H5::H5File file(path, H5F_ACC_RDWR);
  H5::Group group = file.createGroup("/tmdem");
  const hsize_t n = p.contacts;
  write_array(group, "body_i", p.body_i.data(), n, 1, H5::PredType::NATIVE_INT32);
  write_array(group, "body_j", p.body_j.data(), n, 1, H5::PredType::NATIVE_INT32);
  write_array(group, "normal", p.normal.data()->data(), n, 3, H5::PredType::NATIVE_DOUBLE);
  write_array(group, "tangent1", p.tangent1.data()->data(), n, 3, H5::PredType::NATIVE_DOUBLE);
  write_array(group, "tangent2", p.tangent2.data()->data(), n, 3, H5::PredType::NATIVE_DOUBLE);
  write_array(group, "gravity_impulse", p.gravity_impulse.data(), 3, 1, H5::PredType::NATIVE_DOUBLE);
  write_scalar(group, "time_step", p.time_step_s, H5::PredType::NATIVE_DOUBLE);
  write_scalar(group, "step", p.step, H5::PredType::NATIVE_INT64);
  write_scalar(group, "dimension", p.dimension, H5::PredType::NATIVE_INT);
  write_scalar(group, "solver_tolerance", p.solver_tolerance, H5::PredType::NATIVE_DOUBLE);
  write_scalar(group, "solver_residual", p.solver_residual, H5::PredType::NATIVE_DOUBLE);
  write_scalar(group, "solver_seconds", p.solver_seconds, H5::PredType::NATIVE_DOUBLE);
  write_scalar(group, "solver_iterations", p.solver_iterations, H5::PredType::NATIVE_INT64);
  write_scalar(group, "omitted_contacts", p.omitted_contacts, H5::PredType::NATIVE_INT64);
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
  if (!fclib_write_local(&local, path.c_str()))
    throw OutputError("cannot write FCLIB problem '" + path + "' (fclib_write_local failed)");
  fclib_solution solution{nullptr, u.data(), r.data(), nullptr};
  if (!fclib_write_solution(&solution, path.c_str()))
    throw OutputError("cannot write the solution into '" + path + "' (fclib_write_solution failed)");
  if (!fclib_write_guesses(1, &solution, path.c_str()))
    throw OutputError("cannot write the guess into '" + path + "' (fclib_write_guesses failed)");
  try {
    const Hdf5ErrorSilence silence;
    write_tmdem_group(p, path);
  } catch (const H5::Exception& e) {
    throw OutputError("cannot write the /tmdem group into '" + path + "': " + e.getDetailMsg());
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
