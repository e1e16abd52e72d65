// PID against hand-computed values (control_toolbox::Pid semantics).
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "tianracer_control/pid.h"

using tianracer_control::Pid;
using tianracer_control::PidGains;

namespace {
constexpr double kTol = 1e-12;
}

TEST(PidGains, IClampIsSymmetric) {
  const PidGains g = PidGains::fromIClamp(1.0, 2.0, 3.0, -4.0, true);
  EXPECT_EQ(g.p, 1.0);
  EXPECT_EQ(g.i, 2.0);
  EXPECT_EQ(g.d, 3.0);
  EXPECT_EQ(g.i_clamp_min, -4.0);
  EXPECT_EQ(g.i_clamp_max, 4.0);
  EXPECT_TRUE(g.antiwindup);
}

TEST(Pid, FirstUpdateHasNoDerivativeTerm) {
  // p = 2, i = 0.5, d = 0.1, i_clamp = 1, dt = 0.1
  Pid pid(PidGains::fromIClamp(2.0, 0.5, 0.1, 1.0));
  // e = 1: P = 2 * 1 = 2; I = 0.1 * 1 = 0.1, i_term = 0.5 * 0.1 = 0.05; D = 0 (first update)
  EXPECT_NEAR(pid.computeCommand(1.0, 0.1), 2.05, kTol);
  // e = 0.5: P = 1; I = 0.1 + 0.05 = 0.15, i_term = 0.075; D = 0.1 * (0.5 - 1) / 0.1 = -0.5
  EXPECT_NEAR(pid.computeCommand(0.5, 0.1), 1.0 + 0.075 - 0.5, kTol);
  // e = 0.5 again: P = 1; I = 0.2, i_term = 0.1; D = 0
  EXPECT_NEAR(pid.computeCommand(0.5, 0.1), 1.1, kTol);
  EXPECT_NEAR(pid.integrator(), 0.2, kTol);
}

TEST(Pid, ResetForgetsDerivativeHistoryAndIntegrator) {
  Pid pid(PidGains::fromIClamp(0.0, 1.0, 1.0, 10.0));
  pid.computeCommand(1.0, 0.5);
  pid.reset();
  EXPECT_EQ(pid.integrator(), 0.0);
  // After reset the first update again has D = 0: I = 0.5 * 3 = 1.5, i_term = 1.5.
  EXPECT_NEAR(pid.computeCommand(3.0, 0.5), 1.5, kTol);
}

TEST(Pid, ThreeArgumentFormUsesTheGivenDerivative) {
  Pid pid(PidGains::fromIClamp(2.0, 0.0, 0.1, 0.0));
  // P = 2 * 1 = 2, D = 0.1 * (-2) = -0.2, even on the first update.
  EXPECT_NEAR(pid.computeCommand(1.0, -2.0, 0.01), 1.8, kTol);
}

TEST(Pid, IntegralTermIsClampedButIntegratorWindsUpWithoutAntiwindup) {
  // p = d = 0, i = 0.5, i_clamp = 1, dt = 1.
  Pid pid(PidGains::fromIClamp(0.0, 0.5, 0.0, 1.0, false));
  EXPECT_NEAR(pid.computeCommand(10.0, 1.0), 1.0, kTol);  // I = 10, 0.5 * 10 = 5 -> 1
  EXPECT_NEAR(pid.computeCommand(10.0, 1.0), 1.0, kTol);  // I = 20 -> 1
  EXPECT_NEAR(pid.integrator(), 20.0, kTol);
  // Unwinding takes as long as winding up.
  EXPECT_NEAR(pid.computeCommand(-10.0, 1.0), 1.0, kTol);   // I = 10 -> 5 -> 1
  EXPECT_NEAR(pid.computeCommand(-10.0, 1.0), 0.0, kTol);   // I = 0
  EXPECT_NEAR(pid.computeCommand(-10.0, 1.0), -1.0, kTol);  // I = -10 -> -5 -> -1
}

TEST(Pid, AntiwindupStopsTheIntegratorAtTheClamp) {
  Pid pid(PidGains::fromIClamp(0.0, 0.5, 0.0, 1.0, true));
  EXPECT_NEAR(pid.computeCommand(10.0, 1.0), 1.0, kTol);  // I = 10 -> clamp to 1 / 0.5 = 2
  EXPECT_NEAR(pid.computeCommand(10.0, 1.0), 1.0, kTol);
  EXPECT_NEAR(pid.integrator(), 2.0, kTol);
  // One step back: I = 2 - 10 = -8 -> -2, i_term = -1 at once.
  EXPECT_NEAR(pid.computeCommand(-10.0, 1.0), -1.0, kTol);
  EXPECT_NEAR(pid.integrator(), -2.0, kTol);
}

TEST(Pid, AsymmetricClamp) {
  PidGains g;
  g.i = 1.0;
  g.i_clamp_min = -0.5;
  g.i_clamp_max = 2.0;
  Pid pid(g);
  EXPECT_NEAR(pid.computeCommand(5.0, 1.0), 2.0, kTol);
  pid.reset();
  EXPECT_NEAR(pid.computeCommand(-5.0, 1.0), -0.5, kTol);
}

TEST(Pid, DefaultClampOfZeroDisablesTheIntegralTermAsInControlToolbox) {
  PidGains g;
  g.p = 1.0;
  g.i = 3.0;
  Pid pid(g);
  EXPECT_NEAR(pid.computeCommand(1.0, 1.0), 1.0, kTol);
}

TEST(Pid, BadStepOrErrorReturnsZeroAndKeepsState) {
  Pid pid(PidGains::fromIClamp(1.0, 1.0, 1.0, 100.0));
  pid.computeCommand(1.0, 0.1);  // I = 0.1, last error 1
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(pid.computeCommand(2.0, 0.0), 0.0);
  EXPECT_EQ(pid.computeCommand(2.0, -0.1), 0.0);
  EXPECT_EQ(pid.computeCommand(2.0, nan), 0.0);
  EXPECT_EQ(pid.computeCommand(nan, 0.1), 0.0);
  EXPECT_EQ(pid.computeCommand(inf, 0.1), 0.0);
  EXPECT_EQ(pid.computeCommand(1.0, nan, 0.1), 0.0);
  EXPECT_NEAR(pid.integrator(), 0.1, kTol);
  EXPECT_EQ(pid.lastError(), 1.0);
  // Continues as if nothing happened: P = 2, I = 0.1 + 0.2 = 0.3, D = (2 - 1) / 0.1 = 10.
  EXPECT_NEAR(pid.computeCommand(2.0, 0.1), 2.0 + 0.3 + 10.0, 1e-9);
}
