#pragma once
// InteriorPointSolver's factorisation (CHOLMOD's supernodal Cholesky through Eigen), shared by
// its two source files and kept out of the solver's header: CHOLMOD's headers stay out of the
// solvers' users.

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCore>

#include "mechanics/solvers/InteriorPointSolver.h"

namespace tmdem::mechanics {

struct InteriorPointSolver::Factor {
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt;
};

}  // namespace tmdem::mechanics
