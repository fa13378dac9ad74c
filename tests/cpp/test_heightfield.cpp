#include <gtest/gtest.h>

#include <algorithm>

#include "heightfield.hpp"

using namespace plunge;

namespace {

const Cutter kFlat10{CutterShape::Flat, 5.0, 0.0};

}  // namespace

// A plunge beside a hole meets material; into solid, nothing cut; into its
// own hole, nothing; deeper by less than the skin nothing, by more all of it.
TEST(HeightField, SolidBesideAHoleAndCutIsNothing) {
  HeightField f({-20, -20}, {20, 20}, 0.2, 0.0);
  EXPECT_TRUE(f.contact({0, 0}, kFlat10, -10).solid);
  f.cut({0, 0}, kFlat10, -10);
  const HeightField::Contact beside = f.contact({3, 0}, kFlat10, -10);
  EXPECT_GT(beside.materialCells, 0);
  EXPECT_FALSE(beside.solid);
  const HeightField::Contact again = f.contact({0, 0}, kFlat10, -10);
  EXPECT_EQ(again.materialCells, 0);
  EXPECT_EQ(f.contact({0, 0}, kFlat10, -10.4).materialCells, 0);
  EXPECT_TRUE(f.contact({0, 0}, kFlat10, -11).solid);
}

// The core of a non-centre-cutting tool is clear only over a hole at least as wide.
TEST(HeightField, CoreOverAStartHole) {
  HeightField f({-20, -20}, {20, 20}, 0.1, 0.0);
  const Cutter drill{CutterShape::Flat, 2.0, 0.0};
  f.cut({0, 0}, drill, -10);
  EXPECT_TRUE(f.contact({0, 0}, kFlat10, -10, 1.5).coreClear);
  EXPECT_FALSE(f.contact({0, 0}, kFlat10, -10, 3.0).coreClear);
  EXPECT_FALSE(f.contact({1.5, 0}, kFlat10, -10, 1.5).coreClear);
}

// Heights: a ball cuts its own profile; rapids see the highest stock along the way.
TEST(HeightField, BallProfileAndHighestAlong) {
  HeightField f({-20, -20}, {40, 20}, 0.1, 0.0);
  const Cutter ball{CutterShape::Ball, 5.0, 5.0};
  f.cut({0, 0}, ball, -10);
  EXPECT_NEAR(f.heightAt({0.05, 0.05}), -10.0, 0.01);
  EXPECT_NEAR(f.heightAt({4.05, 0.05}), -10 + 5 - std::sqrt(25 - 4.05 * 4.05), 0.05);
  EXPECT_NEAR(f.highest({0, 0}, 1.0), -10 + 5 - std::sqrt(25 - 1.07 * 1.07), 0.05);
  EXPECT_DOUBLE_EQ(f.highestAlong({0, 0}, {20, 0}, 1.0), 0.0);  // across uncut stock
  EXPECT_DOUBLE_EQ(f.highest({100, 100}, 1.0), 0.0);            // beyond the field: the top
}
