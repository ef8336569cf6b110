// When the particle loops use OpenMP threads. Below this many particles a time step takes well
// under a millisecond and the fork/join of a parallel region costs more than it saves (on a loaded
// machine much more: a descheduled thread stalls every barrier), so small runs stay on one thread.
// Results do not depend on this choice: every loop gathers per particle.
#pragma once

#include <Eigen/Core>

namespace hydrojump::sph {

constexpr Eigen::Index kMinParticlesForThreads = 8000;

inline bool use_threads(Eigen::Index particles) { return particles >= kMinParticlesForThreads; }

}  // namespace hydrojump::sph
