#include "thermal/integrators/KluFactorisationCost.h"

#include <sunlinsol/sunlinsol_klu.h>

#include <chrono>
#include <string>
#include <vector>

#include "thermal/integrators/ThermalSolverError.h"

namespace tmdem::thermal {

namespace {

using Clock = std::chrono::steady_clock;

// KLU's solve in SUNDIALS' index type (sunlinsol_klu.h maps the other calls only).
sunindextype klu_solve_in_place(sun_klu_symbolic* symbolic, sun_klu_numeric* numeric,
                                sunindextype n, double* b, sun_klu_common* common) {
#if defined(SUNDIALS_INT64_T)
  return klu_l_solve(symbolic, numeric, n, 1, b, common);
#else
  return klu_solve(symbolic, numeric, n, 1, b, common);
#endif
}

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// KLU's analysis of the pattern, freed on every path.
class KluAnalysis {
 public:
  explicit KluAnalysis(const JacobianPattern& pattern)
      : n_(sunindextype(pattern.size())),
        column_start_(pattern.column_start.begin(), pattern.column_start.end()),
        row_index_(pattern.row_index.begin(), pattern.row_index.end()) {
    sun_klu_defaults(&common_);
    common_.ordering = 0;  // AMD, as SundialsIntegratorBase::create_linear_solver sets it
    symbolic_ = sun_klu_analyze(n_, column_start_.data(), row_index_.data(), &common_);
    if (!symbolic_) fail("symbolic analysis");
  }
  ~KluAnalysis() {
    if (numeric_) sun_klu_free_numeric(&numeric_, &common_);
    if (symbolic_) sun_klu_free_symbolic(&symbolic_, &common_);
  }
  KluAnalysis(const KluAnalysis&) = delete;
  KluAnalysis& operator=(const KluAnalysis&) = delete;

  KluFactorisationCost cost() const { return {symbolic_->est_flops, symbolic_->lnz + symbolic_->unz}; }

  void time(KluFactorisationCost& cost) {
    std::vector<double> values(row_index_.size(), -1.0);
    for (sunindextype j = 0; j < n_; ++j)
      for (auto k = column_start_[std::size_t(j)]; k < column_start_[std::size_t(j) + 1]; ++k)
        if (row_index_[std::size_t(k)] == j)
          values[std::size_t(k)] =
              double(column_start_[std::size_t(j) + 1] - column_start_[std::size_t(j)]);
    auto start = Clock::now();
    numeric_ = sun_klu_factor(column_start_.data(), row_index_.data(), values.data(), symbolic_,
                              &common_);
    if (!numeric_) fail("factorisation");
    cost.factorisation_s = seconds_since(start);
    std::vector<double> b(std::size_t(n_), 1.0);
    start = Clock::now();
    if (!klu_solve_in_place(symbolic_, numeric_, n_, b.data(), &common_)) fail("solve");
    cost.solve_s = seconds_since(start);
  }

 private:
  [[noreturn]] void fail(const char* what) const {
    throw ThermalSolverError(std::string("KLU's ") + what + " of the " + std::to_string(n_) +
                             "-unknown Jacobian pattern failed (KLU status " +
                             std::to_string(common_.status) + ")");
  }

  sunindextype n_;
  std::vector<sunindextype> column_start_, row_index_;
  sun_klu_common common_{};
  sun_klu_symbolic* symbolic_ = nullptr;
  sun_klu_numeric* numeric_ = nullptr;
};

}  // namespace

KluFactorisationCost analyse_klu_factorisation(const JacobianPattern& pattern) {
  return KluAnalysis(pattern).cost();
}

KluFactorisationCost time_klu_factorisation(const JacobianPattern& pattern) {
  KluAnalysis analysis(pattern);
  auto cost = analysis.cost();
  analysis.time(cost);
  return cost;
}

}  // namespace tmdem::thermal
