#include "reference/line_samples.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace hydrojump::reference {

LineSample read_line_sample(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error("cannot read the line sample " + file.string());
  LineSample s;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    double p = 0.0, a = 0.0;
    if (!(ss >> p >> a)) throw std::runtime_error("malformed line in " + file.string() + ": " + line);
    s.position_m.push_back(p);
    s.alpha.push_back(a);
  }
  if (s.position_m.empty()) throw std::runtime_error("the line sample " + file.string() + " holds no data");
  return s;
}

// h = sum over segments of (alpha_i + alpha_{i+1}) / 2 * (s_{i+1} - s_i)
double water_depth(const LineSample& line) {
  double h = 0.0;
  for (std::size_t i = 0; i + 1 < line.position_m.size(); ++i) {
    h += 0.5 * (line.alpha[i] + line.alpha[i + 1]) * (line.position_m[i + 1] - line.position_m[i]);
  }
  return h;
}

std::optional<double> surge_front(const LineSample& line, double max_gap_m) {
  if (line.alpha.empty() || line.alpha.front() < 0.5) return std::nullopt;
  double front = line.position_m.front();
  for (std::size_t i = 1; i < line.alpha.size(); ++i) {
    if (line.alpha[i] >= 0.5) {
      if (line.position_m[i] - front > max_gap_m) break;  // a detached splash ahead of the front
      front = line.position_m[i];
    }
  }
  return front;
}

}  // namespace hydrojump::reference
