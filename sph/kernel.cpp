#include "sph/kernel.hpp"

#include <stdexcept>

namespace hydrojump::sph {

Kernel Kernel::make(const std::string& name, double h_m) {
  if (!(h_m > 0.0)) throw std::invalid_argument("sph kernel: smoothing length h must be > 0, got " + std::to_string(h_m));
  Kernel k;
  k.name_ = name;
  k.h_ = h_m;
  if (name == "wendland_c2") k.wendland_ = true;
  else if (name == "cubic_spline") k.wendland_ = false;
  else throw std::invalid_argument("sph.kernel = \"" + name + "\" is not allowed: use \"wendland_c2\" or \"cubic_spline\"");
  return k;
}

}  // namespace hydrojump::sph
