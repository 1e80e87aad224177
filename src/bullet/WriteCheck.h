// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

// The check after each of ThinTool's writes into Bullet's state: a soft node's position or velocity,
// a dynamic tool's velocities. Every write refuses values that are not finite, so a write that
// leaves a finite value not finite is ThinTool's own fault (an overflow, a write the refusals
// missed): it is counted in the tool's report (ToolDiagnostics::nonFiniteWrites, expected 0) and
// is a failed internal check (core/Assert.h) where those are compiled in. A value that was not
// finite before the write is Bullet's or the program's, and is not counted.

#include <thintool/core/Math.h>

#include <LinearMath/btVector3.h>

class btRigidBody;

namespace thintool::detail {

class DynamicBody;

/// Counts in count a write that turned before, a finite value, into after, one that is not.
void checkWrite(const btVector3& before, const btVector3& after, Index& count);

/// A dynamic tool's velocities before a write, to check them after it; no body, nothing to check.
class BodyVelocities {
 public:
  explicit BodyVelocities(const btRigidBody* body);
  explicit BodyVelocities(const DynamicBody& body);
  void check(Index& count) const;

 private:
  const btRigidBody* m_body = nullptr;
  const DynamicBody* m_link = nullptr;  // a multibody link: its joint velocities, checked together
  bool m_linkFinite = true;
  btVector3 m_linear{0, 0, 0};
  btVector3 m_angular{0, 0, 0};
};

}  // namespace thintool::detail
