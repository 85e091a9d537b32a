#include <gtest/gtest.h>

#include <cmath>

#include "marble_maze/axis_slots.h"

namespace marble_maze {
namespace {

TEST(AxisSlots, AlternatingBoundariesAndWidths) {
  const AxisSlots axis(0.005, 0.02, 5);  // thin, wide, thin, wide, thin
  EXPECT_DOUBLE_EQ(axis.lower(0), 0.0);
  EXPECT_DOUBLE_EQ(axis.lower(1), 0.005);
  EXPECT_DOUBLE_EQ(axis.lower(2), 0.025);
  EXPECT_DOUBLE_EQ(axis.upper(4), 0.055);
  EXPECT_DOUBLE_EQ(axis.length(), 0.055);
  EXPECT_DOUBLE_EQ(axis.width(3), 0.02);
  EXPECT_DOUBLE_EQ(axis.centre(1), 0.015);
}

TEST(AxisSlots, SlotAtFindsTheSlotAndUpperOnBoundaries) {
  const AxisSlots axis(0.005, 0.02, 5);
  EXPECT_EQ(axis.slotAt(0.001), 0);
  EXPECT_EQ(axis.slotAt(0.005), 1);  // a boundary belongs to the upper slot
  EXPECT_EQ(axis.slotAt(0.0249), 1);
  EXPECT_EQ(axis.slotAt(0.03), 2);
  EXPECT_EQ(axis.slotAt(-0.001), -1);
  EXPECT_EQ(axis.slotAt(-0.01), -1);   // slot -1 is [-0.02, 0)
  EXPECT_EQ(axis.slotAt(-0.021), -2);  // slot -2 is [-0.025, -0.02)
  EXPECT_EQ(axis.slotAt(1.0), 80);     // beyond the grid: unclamped
  for (int k = -4; k < 12; ++k) EXPECT_EQ(axis.slotAt(axis.centre(k)), k) << "slot " << k;
}

TEST(AxisSlots, UniformIsTheEqualWidthCase) {
  const AxisSlots axis = AxisSlots::uniform(0.01, 100);
  EXPECT_TRUE(axis.isUniform());
  EXPECT_NEAR(axis.length(), 1.0, 1e-12);
  for (int k = 0; k < 100; ++k) EXPECT_EQ(axis.slotAt(axis.centre(k)), k);
}

TEST(AxisSlots, NonFiniteCoordinatesGiveAnIndexOutsideAnyGrid) {
  const AxisSlots axis(0.005, 0.02, 5);
  const int nan_slot = axis.slotAt(std::nan(""));
  EXPECT_TRUE(nan_slot < 0 || nan_slot >= axis.count());
  EXPECT_GE(axis.slotAt(1e300), axis.count());
  EXPECT_LT(axis.slotAt(-1e300), 0);
}

}  // namespace
}  // namespace marble_maze
