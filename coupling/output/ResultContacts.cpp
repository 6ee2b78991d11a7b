#include "coupling/output/ResultContacts.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "coupling/output/Hdf5Io.h"

namespace tmdem::coupling {
namespace {

constexpr const char* kContactBlocks = "/contacts/blocks";  // BlockSeries of frozen contacts
constexpr auto kRows = BlockSeries::Rows::BlockRows;         // a frame's C contacts per block

// Rows of a contact chunk: about one frame's contacts, within [256, 65536].
hsize_t contact_chunk_rows(std::size_t particles) {
  hsize_t rows = 256;
  while (rows < 3 * particles && rows < 65536) rows *= 2;
  return rows;
}

// f(part, the tail's vector of that part, its memory type) for the five parts in parts() order.
template <class Parts, class Tail, class F>
void with_tail_vectors(const Parts& parts, Tail& t, F&& f) {
  f(parts[0], t.pair, H5T_NATIVE_INT64);
  f(parts[1], t.normal_force_N, H5T_NATIVE_DOUBLE);
  f(parts[2], t.tangential_force_N, H5T_NATIVE_DOUBLE);
  f(parts[3], t.conductance_W_per_K, H5T_NATIVE_DOUBLE);
  f(parts[4], t.heat_flow_W, H5T_NATIVE_DOUBLE);
}

}  // namespace

void ResultContacts::create(hid_t file, std::size_t particles, bool stored,
                            std::size_t frozen_contacts) {
  stored_ = stored;
  file_ = file;
  Hdf5Handle contacts = hdf5::create_group(file, "contacts");
  const hid_t g = contacts.get();
  hdf5::write_int_attribute(g, "stored", stored ? 1 : 0);
  const hsize_t chunk = contact_chunk_rows(particles);
  const hsize_t c = frozen_contacts;
  if (stored && c > 0) {
    pair_blocks_.create(file, "/contacts/pair", kContactBlocks, H5T_STD_I64LE, {c, 2}, kRows, "1");
    normal_force_blocks_.create(file, "/contacts/normal_force", kContactBlocks, H5T_IEEE_F64LE,
                                {c}, kRows, "N");
    tangential_force_blocks_.create(file, "/contacts/tangential_force", kContactBlocks,
                                    H5T_IEEE_F64LE, {c, 3}, kRows, "N");
    conductance_blocks_.create(file, "/contacts/conductance", kContactBlocks, H5T_IEEE_F64LE,
                               {c}, kRows, "W/K");
    pair_ = hdf5::open_dataset(g, "pair");
    normal_force_ = hdf5::open_dataset(g, "normal_force");
    tangential_force_ = hdf5::open_dataset(g, "tangential_force");
    conductance_ = hdf5::open_dataset(g, "conductance");
  } else {
    pair_ = hdf5::create_dataset(g, "pair", H5T_STD_I64LE, {0, 2}, chunk, "1");
    normal_force_ = hdf5::create_dataset(g, "normal_force", H5T_IEEE_F64LE, {0}, chunk, "N");
    tangential_force_ =
        hdf5::create_dataset(g, "tangential_force", H5T_IEEE_F64LE, {0, 3}, chunk, "N");
    conductance_ = hdf5::create_dataset(g, "conductance", H5T_IEEE_F64LE, {0}, chunk, "W/K");
  }
  heat_flow_ = hdf5::create_dataset(g, "heat_flow", H5T_IEEE_F64LE, {0}, chunk, "W");
}

void ResultContacts::open(hid_t file, bool writable) {
  Hdf5Handle contacts = hdf5::open_group(file, "/contacts");
  const hid_t g = contacts.get();
  int stored = 1;
  hdf5::read_int_attribute(g, "stored", stored);
  stored_ = stored != 0;
  file_ = file;
  pair_blocks_.open(file, "/contacts/pair", kContactBlocks, kRows);
  normal_force_blocks_.open(file, "/contacts/normal_force", kContactBlocks, kRows);
  tangential_force_blocks_.open(file, "/contacts/tangential_force", kContactBlocks, kRows);
  conductance_blocks_.open(file, "/contacts/conductance", kContactBlocks, kRows);
  pair_ = hdf5::open_dataset(g, "pair");
  normal_force_ = hdf5::open_dataset(g, "normal_force");
  conductance_ = hdf5::open_dataset(g, "conductance");
  if (hdf5::exists(g, "tangential_force")) {
    tangential_force_ = hdf5::open_dataset(g, "tangential_force");
  } else if (writable) {
    const hsize_t rows = hdf5::dataset_rows(pair_.get());
    tangential_force_ =
        hdf5::create_dataset(g, "tangential_force", H5T_IEEE_F64LE, {0, 3}, 256, "N");
    const std::vector<double> zeros(3 * rows, 0.0);
    hdf5::write_rows(tangential_force_.get(), 0, rows, zeros.data(), H5T_NATIVE_DOUBLE);
  }
  if (hdf5::exists(g, "heat_flow")) {
    heat_flow_ = hdf5::open_dataset(g, "heat_flow");
  } else if (writable) {
    const hsize_t rows = hdf5::dataset_rows(pair_.get());
    heat_flow_ = hdf5::create_dataset(g, "heat_flow", H5T_IEEE_F64LE, {0}, 256, "W");
    const std::vector<double> unknown(rows, std::numeric_limits<double>::quiet_NaN());
    hdf5::write_rows(heat_flow_.get(), 0, rows, unknown.data(), H5T_NATIVE_DOUBLE);
  }
}

std::int64_t ResultContacts::rows() const {
  hsize_t rows = hdf5::dataset_rows(pair_.get());
  for (const Hdf5Handle* d : {&normal_force_, &tangential_force_, &conductance_, &heat_flow_}) {
    if (d->valid()) rows = std::min(rows, hdf5::dataset_rows(d->get()));
  }
  return static_cast<std::int64_t>(rows);
}

void ResultContacts::write(const Hdf5Handle& dataset, BlockSeries& blocks, hsize_t at,
                           hsize_t c, const void* data, hid_t memory_type) {
  if (!blocks.active()) {
    hdf5::write_rows(dataset.get(), at, c, data, memory_type);
    return;
  }
  if (c != blocks.block_rows())
    throw std::invalid_argument("ResultContacts: a frozen contact list has " +
                                std::to_string(blocks.block_rows()) + " contacts, the frame " +
                                std::to_string(c));
  blocks.append(file_, std::size_t(at / c), data, memory_type);
}

void ResultContacts::append(std::int64_t first, const FrameView& frame) {
  const hsize_t c = frame.normal_force_N.size();
  if (c == 0) return;
  const hsize_t at = static_cast<hsize_t>(first);
  write(pair_, pair_blocks_, at, c, frame.contact_pair.data(), H5T_NATIVE_INT64);
  write(normal_force_, normal_force_blocks_, at, c, frame.normal_force_N.data(),
        H5T_NATIVE_DOUBLE);
  if (frame.tangential_force_N.empty()) {
    filler_.assign(3 * c, 0.0);
    write(tangential_force_, tangential_force_blocks_, at, c, filler_.data(), H5T_NATIVE_DOUBLE);
  } else {
    write(tangential_force_, tangential_force_blocks_, at, c, frame.tangential_force_N.data(),
          H5T_NATIVE_DOUBLE);
  }
  write(conductance_, conductance_blocks_, at, c, frame.conductance_W_per_K.data(),
        H5T_NATIVE_DOUBLE);
  if (frame.heat_flow_W.empty()) {
    filler_.assign(c, std::numeric_limits<double>::quiet_NaN());
    hdf5::write_rows(heat_flow_.get(), at, c, filler_.data(), H5T_NATIVE_DOUBLE);
  } else {
    hdf5::write_rows(heat_flow_.get(), at, c, frame.heat_flow_W.data(), H5T_NATIVE_DOUBLE);
  }
}

void ResultContacts::cut_back(std::int64_t rows) {
  const std::pair<const Hdf5Handle*, BlockSeries*> parts[] = {
      {&pair_, &pair_blocks_},
      {&normal_force_, &normal_force_blocks_},
      {&tangential_force_, &tangential_force_blocks_},
      {&conductance_, &conductance_blocks_},
      {&heat_flow_, nullptr}};
  for (const auto& [dataset, blocks] : parts) {
    if (blocks != nullptr && blocks->active()) {
      blocks->cut_back(file_, std::size_t(rows) / blocks->block_rows());
    } else if (dataset->valid()) {
      hdf5::set_rows(dataset->get(), static_cast<hsize_t>(rows));
    }
  }
}

std::vector<ResultContacts::Part> ResultContacts::parts() const {
  return {{&pair_, &pair_blocks_, 2},
          {&normal_force_, &normal_force_blocks_, 1},
          {&tangential_force_, &tangential_force_blocks_, 3},
          {&conductance_, &conductance_blocks_, 1},
          {&heat_flow_, nullptr, 1}};
}

hsize_t ResultContacts::last_chunk_start(const Hdf5Handle& dataset, hsize_t rows) {
  Hdf5Handle plist(hdf5::check_id(H5Dget_create_plist(dataset.get()), "contact dataset"), H5Pclose);
  hsize_t chunk[3] = {0, 0, 0};
  if (H5Pget_layout(plist.get()) != H5D_CHUNKED ||
      H5Pget_chunk(plist.get(), 3, chunk) < 1 || chunk[0] == 0)
    return rows;  // not chunked: nothing is rewritten
  return rows == 0 ? 0 : (rows - 1) / chunk[0] * chunk[0];
}

ContactTail ResultContacts::tail(std::int64_t rows) const {
  ContactTail t;
  t.rows = rows;
  t.start = rows;
  for (const Part& p : parts())
    if (p.dataset->valid() && (p.blocks == nullptr || !p.blocks->active()))
      t.start = std::min<std::int64_t>(t.start, std::int64_t(last_chunk_start(*p.dataset, hsize_t(rows))));
  const hsize_t n = hsize_t(rows - t.start);
  const auto read = [&](const Part& p, auto& out, hid_t type) {
    if (!p.dataset->valid() || (p.blocks != nullptr && p.blocks->active()) || n == 0) return;
    out.resize(n * p.columns);
    hdf5::read_rows(p.dataset->get(), hsize_t(t.start), n, out.data(), type);
  };
  with_tail_vectors(parts(), t, read);
  return t;
}

void ResultContacts::restore(const ContactTail& tail) {
  if (tail.empty()) return;
  if (tail.rows != rows())
    throw std::invalid_argument("contact tail of " + std::to_string(tail.rows) + " rows for " +
                                std::to_string(rows()) + " stored contacts");
  const auto put = [&](const Part& p, const auto& values, hid_t type) {
    if (!p.dataset->valid() || (p.blocks != nullptr && p.blocks->active())) return;
    const hsize_t start = last_chunk_start(*p.dataset, hsize_t(tail.rows));
    if (start >= hsize_t(tail.rows)) return;
    if (std::int64_t(start) < tail.start ||
        values.size() != hsize_t(tail.rows - tail.start) * p.columns)
      throw std::invalid_argument("contact tail from row " + std::to_string(tail.start) +
                                  " does not cover the last chunk from row " + std::to_string(start));
    // Shrinking past the chunk drops it, whatever its bytes; the rows go into a fresh chunk.
    hdf5::set_rows(p.dataset->get(), start);
    hdf5::set_rows(p.dataset->get(), hsize_t(tail.rows));
    hdf5::write_rows(p.dataset->get(), start, hsize_t(tail.rows) - start,
                     values.data() + (start - hsize_t(tail.start)) * p.columns, type);
  };
  with_tail_vectors(parts(), tail, put);
}

void ResultContacts::close() {
  for (Hdf5Handle* d : {&pair_, &normal_force_, &tangential_force_, &conductance_, &heat_flow_})
    d->reset();
}

}  // namespace tmdem::coupling
