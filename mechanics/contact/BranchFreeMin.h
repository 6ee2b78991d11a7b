#pragma once
// min(a, b) as a select the compiler keeps branch-free. GCC -O3 turns `x * std::min(1.0, q)`
// back into a branch ("q < 1 ? q x : x", the multiplication by 1 skipped), and in the local
// solve (CoulombCone.h) that branch is stick against slip, a coin toss on a poured bed: 45% of
// it mispredicted on the 2,000 pour at rest (callgrind), and the branch-free select saved 5% of
// a Gauss-Seidel sweep there (measured in development). Only where the branch is that
// unpredictable: a select waits for its operands where a predicted branch does not (the
// rolling limit, NaturalMapResidual.h, keeps its branch). An empty asm
// statement that claims to change the result hides its value from the optimiser; it emits no
// instruction. Same value as std::min(a, b): b < a ? b : a (a when either is NaN).

#include <algorithm>

namespace tmdem::mechanics {

inline double branch_free_min(double a, double b) {
  double m = std::min(a, b);
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
  asm("" : "+x"(m));  // an SSE register: where minsd leaves it
#elif defined(__GNUC__) && defined(__aarch64__)
  asm("" : "+w"(m));  // a SIMD/FP register
#endif
  return m;
}

}  // namespace tmdem::mechanics
