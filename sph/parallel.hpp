// When the particle loops use OpenMP threads. Below this many particles a time step takes well
// under a millisecond and the fork/join of a parallel region costs more than it saves (on a loaded
// machine much more: a descheduled thread stalls every barrier), so small runs stay on one thread.
// Results do not depend on this choice: every loop adds to a particle in a fixed order (the pair
// loop: each particle sums over its own neighbour list, interactions.cpp).
#pragma once

#include <Eigen/Core>

namespace hydrojump::sph {

// Below this many particles a step runs on one thread. Measured on run A at quick (about 7,950
// particles): with a threshold of 8000 it ran on one thread at 150 steps/s; with 4000, on two threads
// at 219 steps/s with the same result to the bit.
constexpr Eigen::Index kMinParticlesForThreads = 4000;

inline bool use_threads(Eigen::Index particles) { return particles >= kMinParticlesForThreads; }

}  // namespace hydrojump::sph
