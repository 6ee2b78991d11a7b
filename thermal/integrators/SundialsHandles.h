#pragma once
// Owners for the SUNDIALS objects an integrator creates: each is a unique_ptr whose deleter is
// the matching SUNDIALS free function, so nothing is freed by hand. Members are destroyed in
// reverse declaration order, so an owner declares them in the order SUNDIALS needs them gone
// last-to-first: context, then vectors, then matrix, then linear solver (which refers to the
// matrix and a template vector), and the solver memory (CVODES/IDAS, in the derived class) goes
// before all of them.
//
// The make_* helpers check the constructor's result and throw ThermalSolverError naming what
// failed, instead of handing a null pointer on.
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

#include <memory>
#include <string>
#include <type_traits>

#include "thermal/integrators/ThermalSolverError.h"

namespace tmdem::thermal {

struct NVectorFree {
  void operator()(N_Vector v) const { N_VDestroy(v); }
};
struct MatrixFree {
  void operator()(SUNMatrix A) const { SUNMatDestroy(A); }
};
struct LinearSolverFree {
  void operator()(SUNLinearSolver s) const { SUNLinSolFree(s); }
};

using NVectorPtr = std::unique_ptr<std::remove_pointer_t<N_Vector>, NVectorFree>;
using MatrixPtr = std::unique_ptr<std::remove_pointer_t<SUNMatrix>, MatrixFree>;
using LinearSolverPtr = std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, LinearSolverFree>;

// A serial vector of `length` entries; `what` names it in the error ("state y").
inline NVectorPtr make_serial_vector(sunindextype length, SUNContext ctx, const char* what) {
  NVectorPtr v(N_VNew_Serial(length, ctx));
  if (!v)
    throw ThermalSolverError(std::string("N_VNew_Serial failed for the ") + what + " (" +
                             std::to_string(length) + " entries)");
  return v;
}

// Wraps a just-created matrix or solver; throws naming the constructor when it returned null.
template <class Owner, class Raw>
Owner checked_sundials_object(Raw raw, const char* constructor) {
  Owner owner(raw);
  if (!owner) throw ThermalSolverError(std::string(constructor) + " failed");
  return owner;
}

}  // namespace tmdem::thermal
