// When the particle loops use OpenMP threads. Below this many particles a time step takes well
// under a millisecond and the fork/join of a parallel region costs more than it saves (on a loaded
// machine much more: a descheduled thread stalls every barrier), so small runs stay on one thread.
// Results do not depend on this choice: every loop gathers per particle.
#pragma once

#include <Eigen/Core>

namespace hydrojump::sph {

// 4000 since session 22: run A at quick (about 7,950 particles with its tailwater held at the downstream
// section) ran on one thread below the former 8000, at 150 steps/s; from 4000 it runs on two threads
// at 219 steps/s with the same result to the bit (README.md, Performance).
constexpr Eigen::Index kMinParticlesForThreads = 4000;

inline bool use_threads(Eigen::Index particles) { return particles >= kMinParticlesForThreads; }

}  // namespace hydrojump::sph
