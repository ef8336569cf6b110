#include "sph/kernel.hpp"

#include <stdexcept>

namespace hydrojump::sph {

Kernel Kernel::make(const std::string& name, double h_m) {
  if (!(h_m > 0.0)) throw std::invalid_argument("sph kernel: smoothing length h must be > 0, got " + std::to_string(h_m));
  Kernel k;
  k.name_ = name;
  k.h_ = h_m;
  k.wendland_ = parse_kernel(name) == KernelType::wendland_c2;
  return k;
}

}  // namespace hydrojump::sph
