#include "thermal/integrators/ThreadedVector.h"

#include <nvector/nvector_openmp.h>
#include <omp.h>

#include <cmath>
#include <string>
#include <vector>

#include "thermal/network/NodeLoopThreads.h"

namespace tmdem::thermal {
// Named, not anonymous: the thermal library is a unity build (one translation unit).
namespace threaded_vector_ops {

// sum_i term(i) in a fixed order on the vector's threads: static blocks summed in index order,
// then the blocks' sums in thread order (one block: the serial loop's order, bit for bit).
template <class Term>
double fixed_order_sum(N_Vector v, Term term) {
  const auto n = std::int64_t(NV_LENGTH_OMP(v));
  const int threads = NV_NUM_THREADS_OMP(v);
  std::vector<double> block_sum(std::size_t(threads), 0.0);
  int team = 1;
#pragma omp parallel num_threads(threads)
  {
    const int t = omp_get_thread_num();
    const int nt = omp_get_num_threads();
#pragma omp single
    team = nt;
    const std::int64_t begin = n * t / nt, end = n * (t + 1) / nt;
    double sum = 0.0;
    for (std::int64_t i = begin; i < end; ++i) sum += term(std::size_t(i));
    block_sum[std::size_t(t)] = sum;
  }
  double sum = 0.0;
  for (int t = 0; t < team; ++t) sum += block_sum[std::size_t(t)];
  return sum;
}

const double* values(N_Vector v) { return NV_DATA_OMP(v); }

sunrealtype dot(N_Vector x, N_Vector y) {
  const double *xd = values(x), *yd = values(y);
  return fixed_order_sum(x, [=](std::size_t i) { return xd[i] * yd[i]; });
}

sunrealtype weighted_square_sum(N_Vector x, N_Vector w) {
  const double *xd = values(x), *wd = values(w);
  return fixed_order_sum(x, [=](std::size_t i) {
    const double p = xd[i] * wd[i];
    return p * p;
  });
}

sunrealtype weighted_square_sum_masked(N_Vector x, N_Vector w, N_Vector id) {
  const double *xd = values(x), *wd = values(w), *idd = values(id);
  return fixed_order_sum(x, [=](std::size_t i) {
    if (!(idd[i] > 0.0)) return 0.0;  // adding 0.0 to a sum leaves its bits
    const double p = xd[i] * wd[i];
    return p * p;
  });
}

sunrealtype l1_norm(N_Vector x) {
  const double* xd = values(x);
  return fixed_order_sum(x, [=](std::size_t i) { return std::abs(xd[i]); });
}

// The serial vector's formulas on top of the fixed-order sums.
sunrealtype wrms_norm(N_Vector x, N_Vector w) {
  return std::sqrt(weighted_square_sum(x, w) / double(NV_LENGTH_OMP(x)));
}
sunrealtype wrms_norm_masked(N_Vector x, N_Vector w, N_Vector id) {
  return std::sqrt(weighted_square_sum_masked(x, w, id) / double(NV_LENGTH_OMP(x)));
}
sunrealtype wl2_norm(N_Vector x, N_Vector w) { return std::sqrt(weighted_square_sum(x, w)); }

}  // namespace threaded_vector_ops

NVectorPtr make_threaded_vector(sunindextype length, int threads, SUNContext ctx, const char* what) {
  if (threads <= 1) return make_serial_vector(length, ctx, what);
  NVectorPtr v(N_VNew_OpenMP(length, threads, ctx));
  if (!v)
    throw ThermalSolverError(std::string("N_VNew_OpenMP failed for the ") + what + " (" +
                             std::to_string(length) + " entries, " + std::to_string(threads) +
                             " threads)");
  // The fused and array operations stay off (SUNDIALS' default), so every sum goes through
  // the operations below; the max, min and quotient reductions are exact in any order.
  N_VEnableFusedOps_OpenMP(v.get(), SUNFALSE);
  using namespace threaded_vector_ops;
  auto* ops = v->ops;
  ops->nvdotprod = &dot;
  ops->nvdotprodlocal = &dot;
  ops->nvwrmsnorm = &wrms_norm;
  ops->nvwrmsnormmask = &wrms_norm_masked;
  ops->nvwl2norm = &wl2_norm;
  ops->nvl1norm = &l1_norm;
  ops->nvl1normlocal = &l1_norm;
  ops->nvwsqrsumlocal = &weighted_square_sum;
  ops->nvwsqrsummasklocal = &weighted_square_sum_masked;
  return v;
}

NVectorPtr make_state_vector(sunindextype length, SUNContext ctx, const char* what) {
  return make_threaded_vector(length, node_loop_threads(std::size_t(length)), ctx, what);
}

}  // namespace tmdem::thermal
