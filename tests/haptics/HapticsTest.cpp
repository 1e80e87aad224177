// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include <thintool/core/Error.h>
#include <thintool/haptics/ClampMapping.h>
#include <thintool/haptics/HapticLoop.h>
#include <thintool/haptics/ReplayDevice.h>

#include <gtest/gtest.h>

#include <limits>

#include <chrono>
#include <cmath>
#include <sstream>
#include <thread>

namespace thintool::haptics {
namespace {

TEST(ClampMapping, TwoAxesMoveThePlaneAndTheThirdOpens) {
  ClampMapping mapping;
  mapping.deviceCentre = {0, 0, 0.11};
  DeviceState at;
  at.position = {0.01, -0.02, 0.11};
  ClampCommand command = mapDeviceToClamp(at, mapping);
  EXPECT_NEAR(command.planeX, 0.1, 1e-12);
  EXPECT_NEAR(command.planeY, -0.2, 1e-12);
  EXPECT_NEAR(command.opening, mapping.openingAtCentre, 1e-12);
  at.position.z -= 0.01;  // pushed away from the user: closes
  EXPECT_NEAR(mapDeviceToClamp(at, mapping).opening, mapping.openingAtCentre - 0.3, 1e-12);
}

TEST(VirtualCoupling, PullsTheDeviceTowardsTheToolWithinItsLimit) {
  CouplingSettings coupling;  // 3 N/mm, 8 N
  const Vec3 small = couplingForce(coupling, {0, 0, 0}, {}, {0, 0.001, 0}, {});
  EXPECT_NEAR(small.y, 3, 1e-12);
  const Vec3 large = couplingForce(coupling, {0, 0, 0}, {}, {0.01, 0, 0}, {});
  EXPECT_NEAR(length(large), 8, 1e-12);
  EXPECT_GT(large.x, 0);
  EXPECT_NEAR(couplingForceUnclamped(coupling, {}, {}, {0.01, 0, 0}, {}).x, 30, 1e-12);
  EXPECT_EQ(length(couplingForce(coupling, {}, {}, {std::nan(""), 0, 0}, {})), 0);
}

TEST(VirtualCoupling, StabilityCheckIsTheHoldsNegativeDamping) {
  CouplingSettings coupling;
  coupling.stiffness = 3000;
  coupling.damping = 3;
  const CouplingCheck check = checkStability(coupling, 0.001, 0);
  EXPECT_NEAR(check.minimumDamping, 1.5, 1e-12);
  EXPECT_TRUE(check.stable);
  EXPECT_FALSE(check.passive);  // a device without damping of its own is never strictly passive
  coupling.damping = 1.0;
  EXPECT_FALSE(checkStability(coupling, 0.001, 0).stable);
  EXPECT_TRUE(checkStability(coupling, 0.001, 5).passive);
}

// A device handle of mass m whose motor holds each commanded force for one tick, integrated
// exactly over the tick, with no hand on it: the worst case for a sampled coupling.
class SimulatedDevice final : public Device {
 public:
  SimulatedDevice(Real mass, Real period, const Vec3& start) : m_mass(mass), m_period(period), m_position(start) {}
  std::string name() const override { return "simulated mass"; }
  DeviceLimits limits() const override { return DeviceLimits{100, 0}; }
  bool read(double now, DeviceState& out) override {
    out.time = now;
    out.position = m_position;
    return true;
  }
  void write(const Vec3& force) override {
    m_position += m_velocity * m_period + force * (m_period * m_period / (2 * m_mass));
    m_velocity += force * (m_period / m_mass);
  }
  Real energy(Real stiffness) const {
    return 0.5 * m_mass * lengthSquared(m_velocity) + 0.5 * stiffness * lengthSquared(m_position);
  }
  const Vec3& position() const { return m_position; }

 private:
  Real m_mass;
  Real m_period;
  Vec3 m_position;
  Vec3 m_velocity;
};

struct CouplingRun {
  Real largestEnergyRatio = 0;
  Real lateAmplitude = 0;  ///< largest |x| over the last 0.1 s, as a fraction of the start
};

// The hand lets go of the handle 2 mm from a tool held still at the origin (in tissue, say).
CouplingRun letGo(Real damping) {
  const Real period = 0.001;
  HapticLoopSettings settings;
  settings.coupling.stiffness = 3000;  // the Falcon's 3 N/mm
  settings.coupling.damping = damping;
  settings.coupling.maxForce = 100;
  SimulatedDevice device(0.1, period, {0.002, 0, 0});
  HapticLoop loop(device, settings);
  loop.publishTool({}, {});
  const Real start = device.energy(3000);
  CouplingRun run;
  for (int i = 0; i < 1000; ++i) {
    loop.tick(i * period);
    run.largestEnergyRatio = std::max(run.largestEnergyRatio, device.energy(3000) / start);
    if (i >= 900) {
      run.lateAmplitude = std::max(run.lateAmplitude, length(device.position()) / 0.002);
    }
  }
  return run;
}

TEST(VirtualCoupling, AtTheFalconsStiffnessItNeitherGainsEnergyNorOscillates) {
  const CouplingRun run = letGo(CouplingSettings{}.damping);
  // The first tick holds the full spring force for 1 ms before damping sees any motion.
  EXPECT_LT(run.largestEnergyRatio, 1.001);
  // B − K·T/2 = 1.5 N·s/m is left to damp the 0.1 kg handle: the ringing dies within a second.
  EXPECT_LT(run.lateAmplitude, 1e-2);
}

TEST(VirtualCoupling, BelowTheBoundTheHoldPumpsEnergyIn) {
  const CouplingRun undamped = letGo(0);
  EXPECT_GT(undamped.largestEnergyRatio, 10);
  const CouplingRun belowBound = letGo(0.75);  // K·T/4
  EXPECT_GT(belowBound.largestEnergyRatio, 10);
}

const char* kTrajectory =
    "time,x,y,z,buttons\n"
    "0.0,0,0.1,0,0\n"
    "# the press\n"
    "1.0,0,0.0,0,1\n"
    "2.0,0.2,0.0,0,0\n";

TEST(ReplayDevice, InterpolatesAndEnds) {
  std::istringstream in(kTrajectory);
  ReplayDevice device = ReplayDevice::fromStream(in, "press.csv");
  EXPECT_EQ(device.samples().size(), 3u);
  EXPECT_DOUBLE_EQ(device.duration(), 2.0);
  DeviceState state;
  ASSERT_TRUE(device.read(0.25, state));
  EXPECT_NEAR(state.position.y, 0.075, 1e-12);
  EXPECT_EQ(state.buttons, 0u);
  ASSERT_TRUE(device.read(1.5, state));
  EXPECT_NEAR(state.position.x, 0.1, 1e-12);
  EXPECT_EQ(state.buttons, 1u);
  ASSERT_TRUE(device.read(0.5, state));  // back in time
  EXPECT_NEAR(state.position.y, 0.05, 1e-12);
  EXPECT_FALSE(device.read(2.001, state));
}

void expectError(const std::string& text, const std::string& expected) {
  std::istringstream in(text);
  try {
    ReplayDevice::fromStream(in, "bad.csv");
    ADD_FAILURE() << "no error for:\n" << text;
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find(expected), std::string::npos) << error.what();
  }
}

TEST(ReplayDevice, BadFilesNameLineAndField) {
  expectError("0,0,0,0,0\n", "bad.csv:1: expected the header");
  expectError("time,x,y,z,buttons\n0,0,0,0\n", "bad.csv:2: expected 5 fields");
  expectError("time,x,y,z,buttons\n0,0,abc,0,0\n", "bad.csv:2: field 'y': expected a finite number");
  expectError("time,x,y,z,buttons\n0,0,0,nan,0\n", "field 'z'");
  expectError("time,x,y,z,buttons\n0,0,0,0,1.5\n", "field 'buttons'");
  // Two rows a fuzzer wrote: interpolating between them overflowed to infinity.
  expectError("time,x,y,z,buttons\n0,1e308,0,0,0\n1,-1e308,0,0,0\n", "bad.csv:2: field 'x': expected a magnitude");
  expectError("time,x,y,z,buttons\n1,0,0,0,0\n\n1,0,0,0,0\n", "bad.csv:4: field 'time': expected times to increase");
  expectError("time,x,y,z,buttons\n", "no samples");
  EXPECT_THROW(ReplayDevice::fromFile("/nonexistent/trajectory.csv"), Error);
}

TEST(HapticLoop, RunsInItsOwnThreadAndStops) {
  std::istringstream in(kTrajectory);
  ReplayDevice device = ReplayDevice::fromStream(in, "press.csv");
  HapticLoop loop(device, HapticLoopSettings{});
  loop.start();
  loop.publishTool({0, 0.2, 0}, {});  // the tool lags 10 cm above the device: pulled up
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (loop.statistics().ticks < 50 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  loop.stop();
  EXPECT_FALSE(loop.running());
  EXPECT_GE(loop.statistics().ticks, 50u);
  EXPECT_TRUE(loop.device().valid);
  EXPECT_NEAR(length(device.lastForce()), 8, 1e-9) << "clamped to the Falcon's limit";
  EXPECT_GT(device.lastForce().y, 0);
  EXPECT_GT(loop.statistics().clampedTicks, 0u);
  // The tool feels the opposite of the unclamped coupling.
  EXPECT_LT(loop.toolForce({0, 0.2, 0}, {}).y, -8);
}

TEST(HapticLoop, ReplayedAsFastAsPossibleEndsWithTheRecording) {
  std::istringstream in(kTrajectory);
  ReplayDevice device = ReplayDevice::fromStream(in, "press.csv");
  HapticLoop loop(device, HapticLoopSettings{});
  int ticks = 0;
  while (loop.tick(ticks * 0.001)) {
    ++ticks;
  }
  EXPECT_EQ(ticks, 2001);
  EXPECT_TRUE(loop.device().finished);
  EXPECT_EQ(length(device.lastForce()), 0) << "the device is released when the recording ends";
  EXPECT_NEAR(loop.statistics().rate, 1000, 1e-6);
}

TEST(HapticLoop, AToolForceIsRenderedScaledAddedToTheCouplingAndClamped) {
  // A device held still at the origin; the tool, never published, sits on the device's point, so
  // the coupling pulls nowhere and the device feels the rendered force alone.
  ReplayDevice device({{0, {0, 0, 0}, 0}, {10, {0, 0, 0}, 0}});
  HapticLoopSettings settings;
  settings.workspaceScale = 20;
  HapticLoop loop(device, settings);
  ASSERT_TRUE(loop.tick(0));
  EXPECT_EQ(length(device.lastForce()), 0);
  loop.publishToolForce({0, -10, 2});  // N, world: a grasped body's weight and a sideways pull
  ASSERT_TRUE(loop.tick(0.001));
  EXPECT_NEAR(device.lastForce().x, 0, 1e-12);
  EXPECT_NEAR(device.lastForce().y, -0.5, 1e-12) << "divided by the workspace's scale, as the coupling's is";
  EXPECT_NEAR(device.lastForce().z, 0.1, 1e-12);
  loop.publishToolForce({0, std::numeric_limits<Real>::quiet_NaN(), 0});
  ASSERT_TRUE(loop.tick(0.002));
  EXPECT_NEAR(device.lastForce().y, -0.5, 1e-12) << "a force that is not finite is ignored";
  loop.publishToolForce({0, -1000, 0});
  ASSERT_TRUE(loop.tick(0.003));
  EXPECT_NEAR(device.lastForce().y, -8, 1e-12) << "clamped to the device's limit";
  EXPECT_EQ(loop.statistics().clampedTicks, 1u);
}

}  // namespace
}  // namespace thintool::haptics
