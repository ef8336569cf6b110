#include "util/fingerprint.hpp"

#include <cstdint>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace hydrojump::util {

std::string read_text_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// h_0 = 14695981039346656037;  h_{i+1} = (h_i xor byte_i) * 1099511628211  (mod 2^64)
std::string fingerprint(std::string_view text) {
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char ch : text) {
    h ^= ch;
    h *= 1099511628211ull;
  }
  std::ostringstream o;
  o << std::hex << std::setw(16) << std::setfill('0') << h;
  return o.str();
}

}  // namespace hydrojump::util
