#pragma once
// Holds the BLAS to one thread while alive. CHOLMOD's supernodal Cholesky (the interior point's
// factorisation) hands its dense blocks to the BLAS, and Debian's OpenBLAS splits them over
// OMP_NUM_THREADS (or OPENBLAS_NUM_THREADS) threads with blockings that round differently: a
// 2D deposit's settle took another trajectory on 2 threads than on 1 (the same sweeps to the
// bit, then a fallback factorisation apart in the last digits). With the BLAS on one thread the
// fallback gives the same bits for any thread count, as the solvers promise. OpenBLAS is found
// at run time (dlsym); another BLAS is left as it is.

namespace tmdem::mechanics {

class SerialBlas {
 public:
  SerialBlas();
  ~SerialBlas();
  SerialBlas(const SerialBlas&) = delete;
  SerialBlas& operator=(const SerialBlas&) = delete;

  // The BLAS's threads now; 0 when the BLAS is not one whose threads can be set.
  static int threads();
  // Sets them (tests: a BLAS on two threads as OMP_NUM_THREADS=2 gives it); no-op otherwise.
  static void set_threads(int threads);

 private:
  int before_ = 0;  // the threads to give back; 0: nothing was changed
};

}  // namespace tmdem::mechanics
