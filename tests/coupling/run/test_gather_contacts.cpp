// gather_contacts copies the mechanics' contacts in the order they come (no sort): that order
// must already be canonical, and a list that is not is refused rather than silently reordered.
#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "coupling/run/ThermalProblem.h"
#include "mechanics/model/PairIndex.h"

using namespace tmdem;
using namespace tmdem::coupling;

namespace {
mechanics::ContactForce force(std::int64_t i, std::int64_t j, double fn_N) {
  mechanics::ContactForce f;
  f.i = i;
  f.j = j;
  f.normal_force_N = fn_N;
  return f;
}
}  // namespace

TEST(GatherContacts, CopiesCanonicalListAsItComes) {
  const auto wall0 = mechanics::wall_code<std::int64_t>(0);
  const auto wall1 = mechanics::wall_code<std::int64_t>(1);
  const std::vector<mechanics::ContactForce> forces{
      force(0, wall1, 1.0), force(0, wall0, 2.0), force(0, 3, 3.0), force(2, 3, 4.0)};
  ContactList out;
  out.add(7, 8, 9.0);  // stale content is replaced
  gather_contacts(forces, out);
  ASSERT_EQ(out.size(), 4u);
  const std::vector<std::int64_t> pairs{0, -2, 0, -1, 0, 3, 2, 3};
  EXPECT_EQ(out.pair, pairs);
  EXPECT_EQ(out.normal_force_N, (std::vector<double>{1.0, 2.0, 3.0, 4.0}));
}

TEST(GatherContacts, RefusesOutOfOrderOrDuplicateContacts) {
  ContactList out;
  EXPECT_THROW(gather_contacts({force(0, 3, 1.0), force(0, 2, 1.0)}, out), std::logic_error);
  EXPECT_THROW(gather_contacts({force(1, 2, 1.0), force(0, 2, 1.0)}, out), std::logic_error);
  EXPECT_THROW(gather_contacts({force(0, 2, 1.0), force(0, 2, 1.0)}, out), std::logic_error);
}
