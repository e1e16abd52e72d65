// Ackermann kinematics against numbers worked out by hand from the formulas in ackermann.h.
#include <cmath>
#include <limits>
#include <tuple>

#include <gtest/gtest.h>

#include "tianracer_control/ackermann.h"

#include "control_test_support.h"

using namespace tianracer_control;  // NOLINT: test file

namespace {

// Round numbers for hand computation: L = 0.25, T = 0.14 (T/2 = 0.07), r = 0.05, Tr = 0.16,
// m = 0.6.
using test::geometry;
using test::seedGeometry;

constexpr double kTol = 1e-9;

// bicycleAngleFrom{Left,Right} undo {left,right}WheelAngle over +-0.5 rad.
void expectWheelAnglesInvert(const AckermannGeometry& g) {
  for (double delta = -0.5; delta <= 0.5; delta += 0.05) {
    EXPECT_NEAR(bicycleAngleFromLeft(g, leftWheelAngle(g, delta)), delta, kTol);
    EXPECT_NEAR(bicycleAngleFromRight(g, rightWheelAngle(g, delta)), delta, kTol);
  }
}

}  // namespace

TEST(Ackermann, InnerAndOuterAnglesHandComputed) {
  const AckermannGeometry g = geometry();
  // delta = 0.1: tan = 0.100334672085, L tan = 0.025083668021
  //   left  (inner): 0.025083668021 / (0.25 - 0.07 tan = 0.242976572954) -> atan = 0.1028705110
  //   right (outer): 0.025083668021 / (0.25 + 0.07 tan = 0.257023427046) -> atan = 0.0972848462
  EXPECT_NEAR(leftWheelAngle(g, 0.1), 0.1028705110, kTol);
  EXPECT_NEAR(rightWheelAngle(g, 0.1), 0.0972848462, kTol);
  // delta = 0.2: tan = 0.202710035509, L tan = 0.050677508877
  //   left:  / 0.235810297514 -> 0.2116881804;  right: / 0.264189702486 -> 0.1895202829
  EXPECT_NEAR(leftWheelAngle(g, 0.2), 0.2116881804, kTol);
  EXPECT_NEAR(rightWheelAngle(g, 0.2), 0.1895202829, kTol);
  // delta = 0.3: tan = 0.309336249610, L tan = 0.077334062402
  //   left:  / 0.228346462527 -> 0.3265457065;  right: / 0.271653537473 -> 0.2773422636
  EXPECT_NEAR(leftWheelAngle(g, 0.3), 0.3265457065, kTol);
  EXPECT_NEAR(rightWheelAngle(g, 0.3), 0.2773422636, kTol);
  // delta = -0.3, turning right: the right wheel is now the inner one (mirror image).
  EXPECT_NEAR(leftWheelAngle(g, -0.3), -0.2773422636, kTol);
  EXPECT_NEAR(rightWheelAngle(g, -0.3), -0.3265457065, kTol);
  // delta = 0.45: tan = 0.483055065617, L tan = 0.120763766404
  //   left:  / 0.216186145407 -> 0.5094296177;  right: / 0.283813854593 -> 0.4022969733
  EXPECT_NEAR(leftWheelAngle(g, 0.45), 0.5094296177, kTol);
  EXPECT_NEAR(rightWheelAngle(g, 0.45), 0.4022969733, kTol);
  // Straight ahead.
  EXPECT_EQ(leftWheelAngle(g, 0.0), 0.0);
  EXPECT_EQ(rightWheelAngle(g, 0.0), 0.0);
}

TEST(Ackermann, WheelAxesMeetAtTheTurningCentre) {
  // Independent check: the turning centre is on the rear axle line at y = R = L / tan(delta);
  // the left hinge at (L, T/2) must point perpendicular to the ray from the centre.
  const AckermannGeometry g = geometry();
  for (double delta : {0.05, 0.15, 0.25, 0.35, 0.5}) {
    const double R = g.wheelbase / std::tan(delta);
    EXPECT_NEAR(leftWheelAngle(g, delta), std::atan(g.wheelbase / (R - 0.07)), kTol);
    EXPECT_NEAR(rightWheelAngle(g, delta), std::atan(g.wheelbase / (R + 0.07)), kTol);
  }
}

TEST(Ackermann, WheelAngleInversesRoundTrip) {
  expectWheelAnglesInvert(geometry());
}

TEST(Ackermann, YawRateSteeringAngleRoundTrip) {
  const double L = 0.25;
  // v = 0.5, w = 0.5 (R = 1 m): delta = atan(0.25 * 0.5 / 0.5) = atan(0.25) = 0.2449786631
  EXPECT_NEAR(steeringAngleFromYawRate(L, 0.5, 0.5), 0.2449786631, kTol);
  EXPECT_NEAR(yawRateFromSteeringAngle(L, 0.5, std::atan(0.25)), 0.5, kTol);
  for (double v : {-2.0, -0.3, 0.1, 1.0, 3.0}) {
    for (double w : {-1.5, -0.2, 0.0, 0.7, 2.0}) {
      const double delta = steeringAngleFromYawRate(L, v, w);
      EXPECT_NEAR(yawRateFromSteeringAngle(L, v, delta), w, kTol) << v << " " << w;
    }
  }
  // The car cannot turn in place: no steering at v = 0.
  EXPECT_EQ(steeringAngleFromYawRate(L, 0.0, 1.0), 0.0);
  // Reversing with a positive yaw rate steers right (the body still turns left).
  EXPECT_LT(steeringAngleFromYawRate(L, -1.0, 0.5), 0.0);
}

TEST(Ackermann, MaxBicycleAngleHandComputed) {
  const AckermannGeometry g = geometry();
  // tan(0.6) = 0.684136808342; delta_max = atan(0.25 * 0.684136808342 /
  //   (0.25 + 0.07 * 0.684136808342)) = atan(0.171034202085 / 0.297889576584) = 0.5211975241
  EXPECT_NEAR(maxBicycleAngle(g), 0.5211975241, kTol);
  EXPECT_NEAR(leftWheelAngle(g, maxBicycleAngle(g)), 0.6, kTol);
}

TEST(Ackermann, TwistInYawRateMode) {
  const AckermannGeometry g = geometry();
  // v = 0.5, w = 0.5 -> delta = atan(0.25) = 0.2449786631, omega = 0.5 / 0.05 = 10
  const AckermannCommand c = twistToAckermann(g, 0.5, 0.5);
  EXPECT_NEAR(c.delta, 0.2449786631, kTol);
  EXPECT_FALSE(c.clamped);
  EXPECT_NEAR(c.left_steer, leftWheelAngle(g, c.delta), kTol);
  EXPECT_NEAR(c.right_steer, rightWheelAngle(g, c.delta), kTol);
  EXPECT_GT(c.left_steer, c.right_steer);  // left is inner when turning left
  EXPECT_NEAR(c.left_wheel_omega, 10.0, kTol);
  EXPECT_NEAR(c.right_wheel_omega, 10.0, kTol);
  EXPECT_NEAR(c.yaw_rate, 0.5, kTol);
  EXPECT_EQ(c.speed, 0.5);
}

TEST(Ackermann, TwistInSteeringAngleMode) {
  const AckermannGeometry g = geometry();
  AckermannOptions o;
  o.angular_z_is_steering_angle = true;
  const AckermannCommand c = twistToAckermann(g, 1.0, 0.3, o);
  EXPECT_NEAR(c.delta, 0.3, kTol);
  EXPECT_NEAR(c.left_steer, 0.3265457065, kTol);
  EXPECT_NEAR(c.right_steer, 0.2773422636, kTol);
  // w = v tan(0.3) / L = 0.309336249610 / 0.25 = 1.237344998440
  EXPECT_NEAR(c.yaw_rate, 1.237344998440, kTol);
  // Steering-angle mode steers even at standstill.
  EXPECT_NEAR(twistToAckermann(g, 0.0, 0.3, o).delta, 0.3, kTol);
}

TEST(Ackermann, DifferentialRearWheels) {
  const AckermannGeometry g = geometry();
  const AckermannOptions o = test::steeringAngleDifferential();
  // delta = 0.3: k = Tr tan / (2L) = 0.16 * 0.309336249610 / 0.5 = 0.098987599875
  // v = 1, r = 0.05: left = 20 (1 - k) = 18.020248002, right = 20 (1 + k) = 21.979751998
  const AckermannCommand c = twistToAckermann(g, 1.0, 0.3, o);
  EXPECT_NEAR(c.left_wheel_omega, 18.020248002, 1e-8);
  EXPECT_NEAR(c.right_wheel_omega, 21.979751998, 1e-8);
  // The mean is still v / r: the rear axle midpoint runs at v.
  EXPECT_NEAR(0.5 * (c.left_wheel_omega + c.right_wheel_omega), 20.0, kTol);
}

TEST(Ackermann, ClampsSoThatNeitherWheelExceedsTheLimit) {
  const AckermannGeometry g = geometry();
  // v = 0.1, w = 5: delta = atan(0.25 * 5 / 0.1) = atan(12.5), far beyond 0.5211975241.
  const AckermannCommand c = twistToAckermann(g, 0.1, 5.0);
  EXPECT_TRUE(c.clamped);
  EXPECT_NEAR(c.delta, 0.5211975241, kTol);
  EXPECT_LE(c.left_steer, 0.6);
  EXPECT_NEAR(c.left_steer, 0.6, kTol);
  EXPECT_LT(c.right_steer, 0.6);
  // The yaw rate actually reached: v tan(delta_max) / L = 0.1 * 0.574147... / 0.25
  EXPECT_NEAR(c.yaw_rate, 0.1 * std::tan(0.5211975241) / 0.25, 1e-8);

  const AckermannCommand r = twistToAckermann(g, 0.1, -5.0);
  EXPECT_TRUE(r.clamped);
  EXPECT_NEAR(r.right_steer, -0.6, kTol);
  EXPECT_GE(r.right_steer, -0.6);

  AckermannOptions o;
  o.angular_z_is_steering_angle = true;
  EXPECT_TRUE(twistToAckermann(g, 1.0, 1e9, o).clamped);
  EXPECT_FALSE(twistToAckermann(g, 1.0, 0.5, o).clamped);
}

TEST(Ackermann, NonFiniteInputIsTreatedAsZero) {
  const AckermannGeometry g = geometry();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const AckermannCommand c = twistToAckermann(g, nan, nan);
  EXPECT_EQ(c.delta, 0.0);
  EXPECT_EQ(c.left_wheel_omega, 0.0);
  EXPECT_EQ(c.left_steer, 0.0);
}

TEST(Ackermann, GeometryValidation) {
  EXPECT_NO_THROW(AckermannGeometry().validate());
  AckermannGeometry g;
  g.wheelbase = 0.0;
  try {
    g.validate();
    FAIL();
  } catch (const AckermannError& e) {
    EXPECT_NE(std::string(e.what()).find("wheelbase = 0 must be > 0"), std::string::npos)
        << e.what();
  }
  g = AckermannGeometry();
  g.max_steering_angle = 2.0;
  EXPECT_THROW(g.validate(), AckermannError);
  g = AckermannGeometry();
  g.wheel_radius = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(g.validate(), AckermannError);
}

TEST(Ackermann, FromSteeringMatchesTwistInSteeringMode) {
  const AckermannGeometry g = geometry();
  const AckermannOptions o = test::steeringAngleDifferential();
  for (double delta : {-0.7, -0.3, 0.0, 0.2, 0.55}) {
    const AckermannCommand a = twistToAckermann(g, 0.8, delta, o);
    const AckermannCommand b = ackermannFromSteering(g, 0.8, delta, true);
    EXPECT_EQ(a.left_steer, b.left_steer);
    EXPECT_EQ(a.right_wheel_omega, b.right_wheel_omega);
    EXPECT_EQ(a.clamped, b.clamped);
  }
}

TEST(Ackermann, AsymmetricHingesHandComputed) {
  const AckermannGeometry g = seedGeometry();
  // delta = 0.3: R = L / tan(0.3) = 0.24996 / 0.309336249610 = 0.808052... about P.
  //   left hinge (dx, dy) = (0.24868, 0.072994): atan(0.24868 / (R - 0.072994)) = 0.3262256332
  //   right hinge (0.25124, -0.063606):          atan(0.25124 / (R + 0.063606)) = 0.2806258714
  // (the symmetric formulas give 0.3259 and 0.2778: the outer wheel 2.8 mrad short)
  EXPECT_NEAR(leftWheelAngle(g, 0.3), 0.3262256332, kTol);
  EXPECT_NEAR(rightWheelAngle(g, 0.3), 0.2806258714, kTol);
  // delta = -0.3, centre at -R: left (outer) atan(0.24868 / (-R - 0.072994)) = -0.2750987014,
  // right (inner) atan(0.25124 / (-R + 0.063606)) = -0.3254828671: not a mirror image.
  EXPECT_NEAR(leftWheelAngle(g, -0.3), -0.2750987014, kTol);
  EXPECT_NEAR(rightWheelAngle(g, -0.3), -0.3254828671, kTol);
  EXPECT_EQ(leftWheelAngle(g, 0.0), 0.0);
  EXPECT_EQ(rightWheelAngle(g, 0.0), 0.0);
}

TEST(Ackermann, AsymmetricWheelAxesMeetAtTheTurningCentre) {
  // Independent check in base_link coordinates: the centre is on the line through P along y,
  // R from P; each hinge must point perpendicular to the ray from the centre to it.
  const AckermannGeometry g = seedGeometry();
  const double px = -0.12498, py = -0.002347;
  for (double delta : {-0.5, -0.25, -0.05, 0.05, 0.25, 0.5}) {
    const double R = g.wheelbase / std::tan(delta);
    for (const auto& [angle, hx, hy] :
         {std::tuple<double, double, double>{leftWheelAngle(g, delta), 0.1237, 0.070647},
          {rightWheelAngle(g, delta), 0.12626, -0.065953}}) {
      // Ray centre -> hinge: (hx - px, hy - py - R); the wheel rolls along (cos a, sin a),
      // perpendicular to it.
      const double rx = hx - px, ry = hy - py - R;
      EXPECT_NEAR(rx * std::cos(angle) + ry * std::sin(angle), 0.0, 1e-12) << delta;
    }
  }
}

TEST(Ackermann, AsymmetricInversesRoundTrip) {
  expectWheelAnglesInvert(seedGeometry());
}

TEST(Ackermann, AsymmetricLimitsPutTheInnerWheelAtTheJointLimitEitherWay) {
  const AckermannGeometry g = seedGeometry();
  // Left: tan(delta) = L tan(0.6) / (0.24868 + 0.072994 tan(0.6)) -> 0.5200747370
  // Right: tan(delta) = L tan(0.6) / (0.25124 + 0.063606 tan(0.6)) -> 0.5257077143
  EXPECT_NEAR(maxBicycleAngleLeft(g), 0.5200747370, kTol);
  EXPECT_NEAR(maxBicycleAngleRight(g), 0.5257077143, kTol);
  EXPECT_EQ(maxBicycleAngle(g), maxBicycleAngleLeft(g));
  const AckermannCommand l = ackermannFromSteering(g, 1.0, 1e9);
  EXPECT_TRUE(l.clamped);
  EXPECT_NEAR(l.delta, 0.5200747370, kTol);
  EXPECT_NEAR(l.left_steer, 0.6, kTol);
  EXPECT_LT(l.right_steer, 0.6);
  const AckermannCommand r = ackermannFromSteering(g, 1.0, -1e9);
  EXPECT_TRUE(r.clamped);
  EXPECT_NEAR(r.delta, -0.5257077143, kTol);
  EXPECT_NEAR(r.right_steer, -0.6, kTol);
  EXPECT_GT(r.left_steer, -0.6);
  // Between the two limits: not clamped.
  EXPECT_FALSE(ackermannFromSteering(g, 1.0, -0.5230).clamped);
  EXPECT_TRUE(ackermannFromSteering(g, 1.0, 0.5230).clamped);
}

TEST(Ackermann, AsymmetricGeometryValidation) {
  AckermannGeometry g = seedGeometry();
  EXPECT_NO_THROW(g.validate());
  g.hinge_skew_x = 0.3;
  EXPECT_THROW(g.validate(), AckermannError);
  g = seedGeometry();
  g.hinge_offset_y = std::numeric_limits<double>::infinity();
  EXPECT_THROW(g.validate(), AckermannError);
  g = seedGeometry();
  g.rear_axle_y = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(g.validate(), AckermannError);
}
