#pragma once
// The state vectors of the CVODES and IDAS integrators: SUNDIALS' serial vector below
// kThreadedNodes entries or on one thread (thermal/network/NodeLoopThreads.h), else SUNDIALS'
// OpenMP vector on OpenMP's thread count. Its element-wise operations give the serial bits on
// any thread count. Its sums (dot products and norms, which CVODES, IDAS and the CG solver take
// at every step and iteration) are replaced by sums in a fixed order: thread t sums its static
// block in index order, then the blocks' sums are added in thread order. SUNDIALS' own use an
// OpenMP reduction, whose order of combining follows the threads' arrival and so changes bits
// from run to run; with ours the same thread count gives the same bits, and one thread the
// serial vector's.
#include <sundials/sundials_context.h>
#include <sundials/sundials_nvector.h>

#include "thermal/integrators/SundialsHandles.h"

namespace tmdem::thermal {

// A vector of `length` entries on `threads` threads (1: a serial vector); `what` names it in
// the error ("state y"). Clones (SUNDIALS' work vectors) keep the fixed-order sums.
NVectorPtr make_threaded_vector(sunindextype length, int threads, SUNContext ctx, const char* what);

// make_threaded_vector at node_loop_threads(length).
NVectorPtr make_state_vector(sunindextype length, SUNContext ctx, const char* what);

}  // namespace tmdem::thermal
