#pragma once
// Settings of the Moreau-Jean / bipotential contact dynamics ([mechanics] in the scene).

namespace tmdem::mechanics {

struct NscdParameters {
  double time_step = 1.0e-3;  // s
  double theta = 0.5;         // Moreau-Jean theta, in (0, 1]; 0.5 conserves energy in flight
  double tolerance = 1.0e-6;  // Gauss-Seidel stop: sum |dr| / sum |r| over one sweep
  int max_iterations = 10000; // Gauss-Seidel sweeps per step
  // Over-relaxation of the Gauss-Seidel update, r <- proj_K(r + w (r_local - r)); 1 = plain
  // Gauss-Seidel. On frictional piles over-relaxation does not pay (default 256-particle 2D
  // scene: w = 1.3, 1.6, 1.8 gave more unconverged steps and more sweeps than w = 1).
  double relaxation = 1.0;
  // Candidate margin, as fractions of the largest radius (see ContactDetector).
  double min_margin_fraction = 0.1;
  double max_margin_fraction = 2.0;
};

}  // namespace tmdem::mechanics
