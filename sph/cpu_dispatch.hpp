// The hot loops of the solver (the pair loop, the mDBC boundary densities) compiled for three levels
// of x86-64 and one picked when the program loads, for the CPU it runs on (GCC's target_clones, an
// ifunc resolved by the dynamic loader): x86-64-v4 (AVX-512: 32 vector registers, so the pair terms
// keep their operands in registers), x86-64-v3 (AVX2 and FMA) and the baseline. The default build
// stays portable and a user's machine still gets its own instructions; measured on run A at quick
// (one thread, AMD EPYC with AVX-512): 170 -> 190 steps/s, as fast as a -march=native build.
//
// Results differ between the clones at round-off (FMA contracts a * b + c), never with the thread
// count; a resumed run continues bit for bit on the same machine.
//
// sph/CMakeLists.txt defines HYDROJUMP_CPU_CLONES where the compiler can clone function templates
// for these levels (GCC on x86-64; not Clang 14, not other architectures) and the build is not
// already -march=native (HYDROJUMP_NATIVE) nor built with sanitizers (HYDROJUMP_SANITIZE). Elsewhere
// HYDROJUMP_HOT_LOOP is empty.
//
// Usage:
//   template <class K>
//   HYDROJUMP_HOT_LOOP void loop(...) { ... }   // callees it must inline: [[gnu::always_inline]]
// (A clone inlines only always_inline callees compiled for another -march: see interactions.cpp.)
#pragma once

#ifdef HYDROJUMP_CPU_CLONES
#define HYDROJUMP_HOT_LOOP [[gnu::target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")]]
#else
#define HYDROJUMP_HOT_LOOP
#endif
