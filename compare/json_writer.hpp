// A minimal JSON writer for the comparator's outputs (comparison.json of a stilling basin or a dam
// break): objects and arrays with keys in insertion order, strings escaped, numbers with 10
// significant digits, NaN and infinities written as null (JSON has no NaN).
//
// Example:
//   json::Json j;
//   j.begin_object().field("case", "A").field("y2_m", 0.104).end_object();
//   std::string text = j.str();    // {"case": "A", "y2_m": 0.104}
#pragma once

#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

namespace hydrojump::compare::json {

inline std::string json_string(const std::string& s) {
  std::string o = "\"";
  for (char ch : s) {
    switch (ch) {
      case '"': o += "\\\""; break;
      case '\\': o += "\\\\"; break;
      case '\n': o += "\\n"; break;
      case '\t': o += "\\t"; break;
      default:
        if (static_cast<unsigned char>(ch) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", ch);
          o += buf;
        } else {
          o += ch;
        }
    }
  }
  return o + "\"";
}

inline std::string json_number(double v) {
  if (!std::isfinite(v)) return "null";
  std::ostringstream s;
  s << std::setprecision(10) << v;
  return s.str();
}

// Minimal JSON object/array builder (keys in insertion order).
class Json {
 public:
  Json& key(const std::string& k) { sep(); s_ << json_string(k) << ": "; pending_key_ = true; return *this; }
  Json& value(double v) { sep(); s_ << json_number(v); return *this; }
  Json& value(int v) { sep(); s_ << v; return *this; }
  Json& value(bool v) { sep(); s_ << (v ? "true" : "false"); return *this; }
  Json& value(const std::string& v) { sep(); s_ << json_string(v); return *this; }
  Json& value(const char* v) { return value(std::string(v)); }
  Json& begin_object() { sep(); s_ << "{"; first_.push_back(true); return *this; }
  Json& end_object() { s_ << "}"; first_.pop_back(); return *this; }
  Json& begin_array() { sep(); s_ << "["; first_.push_back(true); return *this; }
  Json& end_array() { s_ << "]"; first_.pop_back(); return *this; }
  template <class T> Json& field(const std::string& k, const T& v) { key(k); return value(v); }
  std::string str() const { return s_.str(); }

 private:
  void sep() {
    if (pending_key_) { pending_key_ = false; return; }
    if (!first_.empty()) {
      if (!first_.back()) s_ << ", ";
      first_.back() = false;
    }
  }
  std::ostringstream s_;
  std::vector<bool> first_;
  bool pending_key_ = false;
};

}  // namespace hydrojump::compare::json
