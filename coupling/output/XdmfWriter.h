#pragma once
// RESULT.xdmf: the ParaView description of a tmdem result file, proven by ParaView 5.11's three
// readers (Xdmf3 Reader S, Xdmf3 Reader T and the legacy XDMF Reader; tests/paraview/).
//
// Three temporal collections, one grid per frame each, so that every reader shows them as the
// same blocks at every time (Xdmf3 Reader T: Block0, Block1, Block2; XDMF Reader: by name):
//   particles  Polyvertex on /xdmf/vertices; point attributes temperature (K), velocity (m/s),
//              radius (m), material (index) and id
//   contacts   (when any frame has contacts) a line set: Polyline of 2 nodes per contact on the
//              frame's contact_points; cell attributes normal_force (N), conductance (W/K),
//              heat_flow (W, from i to j or the wall) and tangential_force (N). A frame without
//              contacts has 0 lines (the legacy XDMF Reader then reports an error and shows
//              no contact block for that frame).
//   walls      (scenes with walls) quadrilaterals: a square per plane, 32 strips per cylinder;
//              cell attribute temperature (K, NaN: adiabatic)
// Every DataItem names one whole HDF5 dataset (the per-frame views of ResultViews.h): ParaView's
// Xdmf3 readers show 0 points for HyperSlab items. The HDF5 file is referenced by its file name
// only, so the .xdmf must sit next to the .h5 (both may be moved together).
#include <cstddef>
#include <span>
#include <string>

#include "coupling/output/ResultViews.h"

namespace tmdem::coupling {

// "out/result.h5" -> "out/result.xdmf" (replaces the extension, or appends ".xdmf").
std::string xdmf_path_for(const std::string& h5_path);

// The XDMF text: one frame per entry of times_s, whose views hold views[f] contacts; `walls`
// is the number of wall quadrilaterals (/xdmf/walls/quads).
std::string xdmf_document(const std::string& h5_file_name, std::size_t particles,
                          std::size_t walls, std::span<const double> times_s,
                          std::span<const FrameViewCounts> views);

// Writes xdmf_document(file name of h5_path, ...) to xdmf_path_for(h5_path) through a temporary
// file and a rename, so readers never see a half-written document. Throws OutputError.
void write_xdmf(const std::string& h5_path, std::size_t particles, std::size_t walls,
                std::span<const double> times_s, std::span<const FrameViewCounts> views);

}  // namespace tmdem::coupling
