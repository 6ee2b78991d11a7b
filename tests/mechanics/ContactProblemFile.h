#pragma once
// One contact problem with its warm start, as a text file (a unit-test fixture of a step taken
// from a whole run): every number as a C hexadecimal float ("%a"), so that the problem read
// back is the same bits and a solver repeats the run's solve sweep for sweep.
//
//   # comment lines (where the problem was taken from), anywhere
//   tmdem-contact-problem 1
//   dimension D rolling 0|1 tolerance T
//   bodies B particles P
//   B lines: inverse_mass inverse_inertia free_velocity(3) free_angular_velocity(3)
//   contacts C
//   C lines: body_i body_j normal(3) tangent1(3) tangent2(3) lever_i lever_j w_n w_t bias mu
//            [rolling_limit rolling_radius w_r] r(3) [m(3)]
//
// A step of a whole run has many candidates that stay open through the solve (look-ahead
// detection): keep_contacts() drops them and the bodies only they touch, which leaves the
// solve's sums and velocities bit for bit what they were (an open candidate's visit changes
// nothing and adds 0 to the stop test's sums).

#include <Eigen/Core>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "mechanics/contact/ContactProblem.h"
#include "mechanics/model/PairIndex.h"

namespace tmdem::mechanics::test {

struct ContactProblemFile {
  ContactProblem problem;
  std::vector<Eigen::Vector3d> r, m;  // warm start (m: rolling impulses, sized with rolling)
  double tolerance = 0.0;             // the run's solver tolerance
};

namespace detail {

inline void put(std::ostream& out, double x) {
  char text[40];
  std::snprintf(text, sizeof text, " %a", x);
  out << text;
}
inline void put(std::ostream& out, const Eigen::Vector3d& x) {
  for (int k = 0; k < 3; ++k) put(out, x[k]);
}

// Tokens of the file, numbers parsed with strtod (which reads hexadecimal floats; operator>>
// does not).
class Tokens {
 public:
  explicit Tokens(const std::string& path) : path_(path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cannot open contact problem file " + path);
    // Lines starting with '#' are comments (where the problem comes from).
    for (std::string line; std::getline(in, line);)
      if (line.empty() || line[0] != '#') text_ += line + "\n";
    words_.str(text_);
  }
  std::string word() {
    std::string w;
    if (!(words_ >> w)) throw std::runtime_error(path_ + ": ends early");
    return w;
  }
  void expect(const std::string& w) {
    const std::string got = word();
    if (got != w) throw std::runtime_error(path_ + ": expected '" + w + "', found '" + got + "'");
  }
  double number() {
    const std::string w = word();
    char* end = nullptr;
    const double x = std::strtod(w.c_str(), &end);
    if (end != w.c_str() + w.size()) throw std::runtime_error(path_ + ": not a number: " + w);
    return x;
  }
  long integer() {
    const double x = number();
    if (x != static_cast<double>(static_cast<long>(x)))
      throw std::runtime_error(path_ + ": not an integer");
    return static_cast<long>(x);
  }
  Eigen::Vector3d vector() {
    Eigen::Vector3d x;
    for (int k = 0; k < 3; ++k) x[k] = number();
    return x;
  }

 private:
  std::string path_, text_;
  std::istringstream words_;
};

}  // namespace detail

inline void write_contact_problem(const std::string& path, const ContactProblemFile& f) {
  const ContactProblem& p = f.problem;
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write contact problem file " + path);
  out << "tmdem-contact-problem 1\ndimension " << p.dimension << " rolling " << (p.rolling ? 1 : 0)
      << " tolerance";
  detail::put(out, f.tolerance);
  out << "\nbodies " << p.body_count() << " particles " << p.particle_count << "\n";
  for (std::size_t b = 0; b < p.body_count(); ++b) {
    detail::put(out, p.inverse_mass[b]);
    detail::put(out, p.inverse_inertia[b]);
    detail::put(out, p.free_velocity[b]);
    detail::put(out, p.free_angular_velocity[b]);
    out << "\n";
  }
  out << "contacts " << p.size() << "\n";
  for (std::size_t c = 0; c < p.size(); ++c) {
    out << p.body_i[c] << " " << p.body_j[c];
    for (const Eigen::Vector3d* x : {&p.normal[c], &p.tangent1[c], &p.tangent2[c]}) detail::put(out, *x);
    for (double x : {p.lever_i[c], p.lever_j[c], p.w_n[c], p.w_t[c], p.bias[c], p.mu[c]}) detail::put(out, x);
    if (p.rolling)
      for (double x : {p.rolling_limit[c], p.rolling_radius[c], p.w_r[c]}) detail::put(out, x);
    detail::put(out, f.r[c]);
    if (p.rolling) detail::put(out, f.m[c]);
    out << "\n";
  }
}

inline ContactProblemFile read_contact_problem(const std::string& path) {
  detail::Tokens in(path);
  in.expect("tmdem-contact-problem");
  in.expect("1");
  ContactProblemFile f;
  ContactProblem& p = f.problem;
  in.expect("dimension");
  p.dimension = static_cast<int>(in.integer());
  in.expect("rolling");
  p.rolling = in.integer() != 0;
  in.expect("tolerance");
  f.tolerance = in.number();
  in.expect("bodies");
  const auto bodies = static_cast<std::size_t>(in.integer());
  in.expect("particles");
  p.particle_count = static_cast<std::size_t>(in.integer());
  for (std::size_t b = 0; b < bodies; ++b) {
    p.inverse_mass.push_back(in.number());
    p.inverse_inertia.push_back(in.number());
    p.free_velocity.push_back(in.vector());
    p.free_angular_velocity.push_back(in.vector());
  }
  in.expect("contacts");
  const auto contacts = static_cast<std::size_t>(in.integer());
  p.resize_contacts(contacts);
  f.r.resize(contacts);
  if (p.rolling) f.m.resize(contacts);
  for (std::size_t c = 0; c < contacts; ++c) {
    p.body_i[c] = static_cast<std::int32_t>(in.integer());
    p.body_j[c] = static_cast<std::int32_t>(in.integer());
    p.normal[c] = in.vector();
    p.tangent1[c] = in.vector();
    p.tangent2[c] = in.vector();
    for (double* x : {&p.lever_i[c], &p.lever_j[c], &p.w_n[c], &p.w_t[c], &p.bias[c], &p.mu[c]}) *x = in.number();
    if (p.rolling)
      for (double* x : {&p.rolling_limit[c], &p.rolling_radius[c], &p.w_r[c]}) *x = in.number();
    f.r[c] = in.vector();
    if (p.rolling) f.m[c] = in.vector();
  }
  return f;
}

// The problem of `f` with only the contacts `keep` (in their order) and the particles they
// touch (renumbered in order; the wall bodies all kept).
inline ContactProblemFile keep_contacts(const ContactProblemFile& f, const std::vector<std::size_t>& keep) {
  const ContactProblem& from = f.problem;
  std::vector<std::int32_t> number(from.particle_count, -1);
  for (std::size_t c : keep) {
    number[from.body_i[c]] = 0;
    if (!is_wall(from.body_j[c])) number[from.body_j[c]] = 0;
  }
  ContactProblemFile out;
  out.tolerance = f.tolerance;
  ContactProblem& p = out.problem;
  p.dimension = from.dimension;
  p.rolling = from.rolling;
  for (std::size_t b = 0; b < from.body_count(); ++b) {
    if (b < from.particle_count) {
      if (number[b] < 0) continue;
      number[b] = static_cast<std::int32_t>(p.inverse_mass.size());
    }
    if (b == from.particle_count) p.particle_count = p.inverse_mass.size();
    p.inverse_mass.push_back(from.inverse_mass[b]);
    p.inverse_inertia.push_back(from.inverse_inertia[b]);
    p.free_velocity.push_back(from.free_velocity[b]);
    p.free_angular_velocity.push_back(from.free_angular_velocity[b]);
  }
  if (from.particle_count == from.body_count()) p.particle_count = p.inverse_mass.size();
  p.resize_contacts(keep.size());
  for (std::size_t k = 0; k < keep.size(); ++k) {
    const std::size_t c = keep[k];
    p.copy_contact(k, from, c);
    p.body_i[k] = number[from.body_i[c]];
    if (!is_wall(from.body_j[c])) p.body_j[k] = number[from.body_j[c]];
    out.r.push_back(f.r[c]);
    if (p.rolling) out.m.push_back(f.m[c]);
  }
  return out;
}

}  // namespace tmdem::mechanics::test
