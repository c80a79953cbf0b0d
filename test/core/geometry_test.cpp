#include "swarm_transport/core/geometry.h"

#include <gtest/gtest.h>

#include <cmath>

namespace swarm_transport {
namespace core {
namespace {

constexpr double kTolerance = 1e-9;

void ExpectNear(Vec2 actual, Vec2 expected) {
  EXPECT_NEAR(actual.x, expected.x, kTolerance);
  EXPECT_NEAR(actual.y, expected.y, kTolerance);
}

// An L: a vertical bar [0,1]x[0,3] and a horizontal bar [0,3]x[0,1] that overlap in [0,1]^2.
Shape LShape() {
  return Shape(
      {Primitive::MakeRect({0.5, 1.5}, {1.0, 3.0}), Primitive::MakeRect({1.5, 0.5}, {3.0, 1.0})});
}

TEST(GeometryTest, BearingPointsFromOneToTheOther) {
  EXPECT_EQ(Bearing({1.0, 1.0}, {2.0, 2.0}), Angle(45));
  EXPECT_EQ(Bearing({1.0, 1.0}, {1.0, 0.0}), Angle(270));
  EXPECT_EQ(Bearing({1.0, 1.0}, {1.0, 1.0}), Angle(0));
  ExpectNear(UnitVector(Angle(90)), {0.0, 1.0});
}

TEST(GeometryTest, DistancePointSegmentUsesFootOrEnd) {
  EXPECT_NEAR(DistancePointSegment({1.0, 2.0}, {0.0, 0.0}, {2.0, 0.0}), 2.0, kTolerance);
  EXPECT_NEAR(DistancePointSegment({5.0, 4.0}, {0.0, 0.0}, {2.0, 0.0}), 5.0, kTolerance);
  EXPECT_NEAR(DistancePointSegment({3.0, 4.0}, {0.0, 0.0}, {0.0, 0.0}), 5.0, kTolerance);
}

TEST(GeometryTest, RectContainsItsBorder) {
  const Shape rect = Shape::FromRect({2.0, 2.0}, {2.0, 1.0});
  EXPECT_TRUE(rect.Contains({2.0, 2.0}));
  EXPECT_TRUE(rect.Contains({3.0, 2.5}));
  EXPECT_FALSE(rect.Contains({3.01, 2.0}));
  EXPECT_FALSE(rect.Contains({2.0, 2.51}));
}

TEST(GeometryTest, CircleContainsItsBorder) {
  const Shape circle = Shape::FromCircle({1.0, 1.0}, 1.0);
  EXPECT_TRUE(circle.Contains({2.0, 1.0}));
  EXPECT_FALSE(circle.Contains({1.8, 1.8}));
}

TEST(GeometryTest, DistanceAndNearestPointOfRect) {
  const Shape rect = Shape::FromRect({0.0, 0.0}, {2.0, 2.0});
  EXPECT_NEAR(rect.DistanceTo({4.0, 5.0}), 5.0, kTolerance);
  ExpectNear(rect.NearestPoint({4.0, 5.0}), {1.0, 1.0});
  ExpectNear(rect.NearestPoint({0.5, 5.0}), {0.5, 1.0});
  EXPECT_NEAR(rect.DistanceTo({0.5, 0.5}), 0.0, kTolerance);
  ExpectNear(rect.NearestPoint({0.5, 0.5}), {0.5, 0.5});
}

TEST(GeometryTest, DistanceAndNearestPointOfCircle) {
  const Shape circle = Shape::FromCircle({0.0, 0.0}, 1.0);
  EXPECT_NEAR(circle.DistanceTo({3.0, 4.0}), 4.0, kTolerance);
  ExpectNear(circle.NearestPoint({3.0, 4.0}), {0.6, 0.8});
}

TEST(GeometryTest, UnionUsesTheNearestPart) {
  const Shape shape(
      {Primitive::MakeCircle({0.0, 0.0}, 1.0), Primitive::MakeRect({10.0, 0.0}, {2.0, 2.0})});
  EXPECT_NEAR(shape.DistanceTo({7.0, 0.0}), 2.0, kTolerance);
  ExpectNear(shape.NearestPoint({7.0, 0.0}), {9.0, 0.0});
}

TEST(GeometryTest, EmptyShapeHasNoPoint) {
  const Shape empty;
  EXPECT_FALSE(empty.Contains({0.0, 0.0}));
  EXPECT_TRUE(std::isinf(empty.DistanceTo({0.0, 0.0})));
}

TEST(GeometryTest, CentreIsTheBoundingBoxCentreAndTranslationMovesEveryPart) {
  const Shape shape = LShape();
  ExpectNear(shape.Centre(), {1.5, 1.5});
  const Shape moved = shape.Translated({1.0, 2.0});
  ExpectNear(moved.Centre(), {2.5, 3.5});
  EXPECT_TRUE(moved.Contains({3.5, 2.5}));  // was (2.5, 0.5), in the horizontal bar
  EXPECT_FALSE(moved.Contains({2.5, 0.5}));
}

TEST(GeometryTest, NearestPointOutsideOfAnOutsidePointIsItself) {
  ExpectNear(Shape::FromRect({0.0, 0.0}, {2.0, 2.0}).NearestPointOutside({3.0, 0.0}, 0.1),
             {3.0, 0.0});
}

TEST(GeometryTest, NearestPointOutsideCrossesTheNearestSideByTheMargin) {
  // Right side 0.5 away, top side 0.8 away.
  const Shape rect = Shape::FromRect({0.0, 0.0}, {4.0, 2.0});
  ExpectNear(rect.NearestPointOutside({1.5, 0.2}, 0.1), {2.1, 0.2});
  ExpectNear(rect.NearestPointOutside({1.5, 0.2}, 0.0), {2.0, 0.2});
}

TEST(GeometryTest, NearestPointOutsideKeepsTheMarginFromEveryPart) {
  // The vertical bar's corner (1, 0) lies on the flat bottom of the union: stepping out
  // diagonally there would come closer than the margin.
  const Shape shape = LShape();
  const Vec2 out = shape.NearestPointOutside({0.97, 0.3}, 0.1);
  ExpectNear(out, {0.97, -0.1});
  EXPECT_GE(shape.DistanceTo(out), 0.1 - kTolerance);
}

TEST(GeometryTest, NearestPointOutsideOfTwoCirclesUsesWhereTheyCross) {
  // Circles of radius 1 at (0, 0) and (1.2, 0): from (0.6, 0.7) the nearest way out is where the
  // grown circles (radius 1.1) cross, at (0.6, sqrt(1.1^2 - 0.6^2)).
  const Shape shape(
      {Primitive::MakeCircle({0.0, 0.0}, 1.0), Primitive::MakeCircle({1.2, 0.0}, 1.0)});
  const Vec2 out = shape.NearestPointOutside({0.6, 0.7}, 0.1);
  ExpectNear(out, {0.6, std::sqrt(1.1 * 1.1 - 0.36)});
  EXPECT_FALSE(shape.Contains(out));
}

TEST(GeometryTest, NearestPointOutsideOfCircleIsRadial) {
  ExpectNear(Shape::FromCircle({0.0, 0.0}, 1.0).NearestPointOutside({0.5, 0.0}, 0.1), {1.1, 0.0});
}

TEST(GeometryTest, NearestPointOutsideOfUnionDoesNotLandInAnotherPart) {
  // The vertical bar's right side (1, 0.5) is 0.1 away but inside the horizontal bar; the
  // nearest way out is the bottom, 0.5 away.
  const Shape shape = LShape();
  const Vec2 out = shape.NearestPointOutside({0.9, 0.5}, 0.1);
  ExpectNear(out, {0.9, -0.1});
  EXPECT_FALSE(shape.Contains(out));
}

TEST(GeometryTest, NearestPointOutsideOfUnionCanBeItsInnerCorner) {
  // From (0.95, 0.95) both bars' near sides lie inside the other bar; the way out is past the
  // inner corner (1, 1), to the point the margin away from both bars.
  const Shape shape = LShape();
  const Vec2 out = shape.NearestPointOutside({0.95, 0.95}, 0.1);
  ExpectNear(out, {1.1, 1.1});
  EXPECT_FALSE(shape.Contains(out));
}

TEST(GeometryTest, DangerZoneForbidsItsInside) {
  const Zone danger{1, Shape::FromRect({5.0, 5.0}, {2.0, 2.0}), false};
  EXPECT_TRUE(danger.Forbids({5.0, 5.0}));
  EXPECT_FALSE(danger.Forbids({7.0, 5.0}));
}

TEST(GeometryTest, SafetyZoneForbidsItsOutside) {
  const Zone safety{1, Shape::FromRect({5.0, 5.0}, {2.0, 2.0}), true};
  EXPECT_FALSE(safety.Forbids({5.0, 5.0}));
  EXPECT_TRUE(safety.Forbids({7.0, 5.0}));
}

TEST(GeometryTest, DangerZoneAllowedPointIsJustOutside) {
  const Zone danger{1, Shape::FromRect({5.0, 5.0}, {2.0, 2.0}), false};
  ExpectNear(danger.NearestAllowedPoint({5.0, 5.7}, 0.02), {5.0, 6.02});
  ExpectNear(danger.NearestAllowedPoint({8.0, 8.0}, 0.02), {8.0, 8.0});
}

TEST(GeometryTest, SafetyZoneAllowedPointIsMarginInside) {
  const Zone safety{1, Shape::FromRect({5.0, 5.0}, {2.0, 2.0}), true};
  ExpectNear(safety.NearestAllowedPoint({8.0, 5.5}, 0.1), {5.9, 5.5});
  ExpectNear(safety.NearestAllowedPoint({5.5, 5.5}, 0.1), {5.5, 5.5});
}

TEST(GeometryTest, SafetyCircleAllowedPointIsMarginInside) {
  const Zone safety{1, Shape::FromCircle({0.0, 0.0}, 1.0), true};
  ExpectNear(safety.NearestAllowedPoint({3.0, 0.0}, 0.2), {0.8, 0.0});
}

TEST(GeometryTest, SafetyZoneThinnerThanTwoMarginsAimsAtItsCentreLine) {
  const Zone safety{1, Shape::FromRect({5.0, 5.0}, {0.1, 2.0}), true};
  ExpectNear(safety.NearestAllowedPoint({3.0, 5.5}, 0.1), {5.0, 5.5});
}

TEST(GeometryTest, SafetyUnionAimsAtTheNearestPart) {
  const Zone safety{
      1,
      Shape({Primitive::MakeRect({0.0, 0.0}, {1.0, 1.0}), Primitive::MakeCircle({5.0, 0.0}, 1.0)}),
      true};
  ExpectNear(safety.NearestAllowedPoint({3.0, 0.0}, 0.1), {4.1, 0.0});
  ExpectNear(safety.NearestAllowedPoint({1.0, 0.2}, 0.1), {0.4, 0.2});
}

}  // namespace
}  // namespace core
}  // namespace swarm_transport
