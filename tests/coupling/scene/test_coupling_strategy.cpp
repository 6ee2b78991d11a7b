// thermal.coupling names parse once into the strategy the dynamic step loop compares.
#include <gtest/gtest.h>

#include "coupling/bridge/CouplingStrategy.h"

using namespace tmdem::coupling;

TEST(CouplingStrategy, NamesRoundTripAndUnknownIsRefused) {
  for (auto name : kCouplingStrategyNames) EXPECT_EQ(name_of(parse_coupling_strategy(name)), name);
  EXPECT_EQ(parse_coupling_strategy("restart"), CouplingStrategy::Restart);
  EXPECT_THROW(parse_coupling_strategy("sometimes"), std::invalid_argument);
}
