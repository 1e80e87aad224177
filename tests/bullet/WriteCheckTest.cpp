// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// The check after ThinTool's writes into Bullet's state: it counts, and fails an internal check
// for, a write that left a finite value not finite, and only that.

#include "../../src/bullet/WriteCheck.h"

#include <thintool/core/Assert.h>

#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <gtest/gtest.h>

#include <limits>

namespace thintool::detail {
namespace {

int g_failed = 0;
void countFailure(const char*, const char*, int) { ++g_failed; }

struct CountingHandler {
  AssertHandler previous;
  CountingHandler() : previous(setAssertHandler(countFailure)) { g_failed = 0; }
  ~CountingHandler() { setAssertHandler(previous); }
  CountingHandler(const CountingHandler&) = delete;
  CountingHandler& operator=(const CountingHandler&) = delete;
};

const btScalar kNaN = std::numeric_limits<btScalar>::quiet_NaN();
const btScalar kInfinity = std::numeric_limits<btScalar>::infinity();

TEST(WriteCheck, CountsAWriteThatLeftAFiniteValueNotFinite) {
  CountingHandler handler;
  Index count = 0;
  checkWrite(btVector3(1, 2, 3), btVector3(1, 2.5, 3), count);
  EXPECT_EQ(count, 0u);
  EXPECT_EQ(g_failed, 0);
  checkWrite(btVector3(1, 2, 3), btVector3(1, kNaN, 3), count);
  checkWrite(btVector3(0, 0, 0), btVector3(kInfinity, 0, 0), count);
  EXPECT_EQ(count, 2u);
  // Where the library was built with its internal checks, each is a failed one.
  const int failures = libraryChecksAsserts() ? 2 : 0;
  EXPECT_EQ(g_failed, failures);
  checkWrite(btVector3(kNaN, 0, 0), btVector3(kNaN, 0, 0), count);
  EXPECT_EQ(count, 2u) << "a value that was not finite before is not ThinTool's write";
  EXPECT_EQ(g_failed, failures);
}

TEST(WriteCheck, ChecksABodysVelocitiesAfterAWrite) {
  CountingHandler handler;
  btSphereShape shape(0.1);
  btRigidBody body(1, nullptr, &shape);
  body.setLinearVelocity(btVector3(1, 0, 0));
  Index count = 0;
  const BodyVelocities before(&body);
  body.applyCentralImpulse(btVector3(0, 2, 0));
  before.check(count);
  EXPECT_EQ(count, 0u);
  const BodyVelocities again(&body);
  body.setAngularVelocity(btVector3(0, kNaN, 0));
  again.check(count);
  EXPECT_EQ(count, 1u);
  EXPECT_EQ(g_failed, libraryChecksAsserts() ? 1 : 0);
  const BodyVelocities none(nullptr);
  none.check(count);
  EXPECT_EQ(count, 1u) << "no body, nothing to check";
}

}  // namespace
}  // namespace thintool::detail
