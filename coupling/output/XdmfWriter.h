#pragma once
// XDMF (version 2 syntax, read by ParaView's "XDMF Reader" and "Xdmf3 Reader") describing a
// tmdem result file: a temporal collection with one Polyvertex grid per frame, geometry XYZ from
// a hyperslab of /frames/position, node attributes temperature (K), velocity (m/s), radius (m)
// and material (index). The HDF5 file is referenced by its file name only, so the .xdmf must sit
// next to the .h5 (it stays valid when both are moved together).
#include <cstddef>
#include <span>
#include <string>

namespace tmdem::coupling {

// "out/result.h5" -> "out/result.xdmf" (replaces the extension, or appends ".xdmf").
std::string xdmf_path_for(const std::string& h5_path);

// The XDMF text for `particles` particles and one frame per entry of times_s.
std::string xdmf_document(const std::string& h5_file_name, std::size_t particles,
                          std::span<const double> times_s);

// Writes xdmf_document(file name of h5_path, ...) to xdmf_path_for(h5_path) through a temporary
// file and a rename, so readers never see a half-written document. Throws OutputError.
void write_xdmf(const std::string& h5_path, std::size_t particles,
                std::span<const double> times_s);

}  // namespace tmdem::coupling
