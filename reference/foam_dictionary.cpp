#include "reference/foam_dictionary.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>
#include <system_error>

namespace hydrojump::reference::foam {

namespace {

constexpr int key_column = 16;     // OpenFOAM's tutorials pad keys to 16 characters
constexpr std::size_t inline_list_limit = 100;  // longer lists are written one item per line

std::string indentation(int level) { return std::string(static_cast<std::size_t>(4 * level), ' '); }

bool is_block(const Value& v);

// A list is written on one line when it holds only short scalar-like items.
bool list_is_inline(const Value& v) {
  for (const Value& item : v.items()) {
    if (is_block(item)) return false;
  }
  std::size_t length = 2;
  for (const Value& item : v.items()) length += format_value(item).size() + 1;
  return length <= inline_list_limit;
}

// True for values written over several lines (nested dictionaries, long lists).
bool is_block(const Value& v) {
  switch (v.kind()) {
    case Value::Kind::Dict:
    case Value::Kind::NamedDict:
      return true;
    case Value::Kind::List:
      return !list_is_inline(v);
    default:
      return false;
  }
}

std::string escape_string(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out;
}

}  // namespace

// ---------------------------------------------------------------------------------------------- Value

Value::Value(double number) : kind_(Kind::Number), number_(number) { format_number(number); }
Value::Value(int number) : kind_(Kind::Number), number_(number) {}
Value::Value(const Dictionary& dict)
    : kind_(Kind::Dict), dict_(std::make_shared<Dictionary>(dict)) {}

const Dictionary& Value::dict() const {
  if (!dict_) throw std::logic_error("foam::Value: not a dictionary");
  return *dict_;
}

Value Value::make_word(std::string token) {
  if (token.empty()) throw std::invalid_argument("foam::word: empty token");
  Value v;
  v.kind_ = Kind::Word;
  v.text_ = std::move(token);
  return v;
}

Value Value::make_string(std::string text) {
  Value v;
  v.kind_ = Kind::String;
  v.text_ = std::move(text);
  return v;
}

Value Value::make_sequence(std::vector<Value> tokens) {
  if (tokens.empty()) throw std::invalid_argument("foam::sequence: no tokens");
  Value v;
  v.kind_ = Kind::Sequence;
  v.items_ = std::move(tokens);
  return v;
}

Value Value::make_list(std::vector<Value> items) {
  Value v;
  v.kind_ = Kind::List;
  v.items_ = std::move(items);
  return v;
}

Value Value::make_named_dict(std::string name, const Dictionary& dict) {
  if (name.empty()) throw std::invalid_argument("foam::named_dict: empty name");
  Value v;
  v.kind_ = Kind::NamedDict;
  v.text_ = std::move(name);
  v.dict_ = std::make_shared<Dictionary>(dict);
  return v;
}

Value word(std::string token) { return Value::make_word(std::move(token)); }
Value string(std::string text) { return Value::make_string(std::move(text)); }
Value sequence(std::vector<Value> tokens) { return Value::make_sequence(std::move(tokens)); }
Value list(std::vector<Value> items) { return Value::make_list(std::move(items)); }
Value named_dict(std::string name, const Dictionary& dict) {
  return Value::make_named_dict(std::move(name), dict);
}
Value vector(double x, double y, double z) { return list({Value(x), Value(y), Value(z)}); }
Value uniform(const Value& v) { return sequence({word("uniform"), v}); }
Value on_off(bool on) { return word(on ? "on" : "off"); }
Value yes_no(bool yes) { return word(yes ? "yes" : "no"); }

Value dimensions(const std::array<int, 7>& exponents) {
  std::string text = "[";
  for (std::size_t i = 0; i < exponents.size(); ++i) {
    if (i > 0) text += ' ';
    text += std::to_string(exponents[i]);
  }
  text += ']';
  return word(text);
}

// --------------------------------------------------------------------------------------- Dictionary

Dictionary& Dictionary::set(const std::string& key, const Value& value) {
  if (key.empty()) throw std::invalid_argument("foam::Dictionary::set: empty key");
  for (Entry& e : entries_) {
    if (e.directive.empty() && e.key == key) {
      e.value = value;
      return *this;
    }
  }
  entries_.push_back(Entry{key, value, {}});
  return *this;
}

Dictionary& Dictionary::subdict(const std::string& key) {
  for (Entry& e : entries_) {
    if (e.directive.empty() && e.key == key) {
      if (e.value.kind() != Value::Kind::Dict) {
        throw std::logic_error("foam::Dictionary: entry '" + key + "' is not a dictionary");
      }
      // Values share their dictionary; copy-on-write keeps other holders unchanged.
      e.value.dict_ = std::make_shared<Dictionary>(e.value.dict());
      return *e.value.dict_;
    }
  }
  entries_.push_back(Entry{key, Value(Dictionary{}), {}});
  return *entries_.back().value.dict_;
}

Dictionary& Dictionary::directive(const std::string& line) {
  if (line.empty()) throw std::invalid_argument("foam::Dictionary::directive: empty line");
  entries_.push_back(Entry{{}, Value(0), line});
  return *this;
}

bool Dictionary::contains(const std::string& key) const {
  for (const Entry& e : entries_) {
    if (e.directive.empty() && e.key == key) return true;
  }
  return false;
}

const Value& Dictionary::at(const std::string& key) const {
  for (const Entry& e : entries_) {
    if (e.directive.empty() && e.key == key) return e.value;
  }
  throw std::out_of_range("foam::Dictionary: no entry '" + key + "'");
}

const Dictionary& Dictionary::subdict_at(const std::string& key) const { return at(key).dict(); }

std::vector<std::string> Dictionary::keys() const {
  std::vector<std::string> out;
  for (const Entry& e : entries_) {
    if (e.directive.empty()) out.push_back(e.key);
  }
  return out;
}

std::string Dictionary::format(int indent) const {
  std::string out;
  const std::string pad = indentation(indent);
  for (std::size_t i = 0; i < entries_.size(); ++i) {
    const Entry& e = entries_[i];
    if (!e.directive.empty()) {
      out += pad + e.directive + "\n";
      continue;
    }
    if (is_block(e.value)) {
      if (indent == 0 && !out.empty() && !(out.size() >= 2 && out.compare(out.size() - 2, 2, "\n\n") == 0)) {
        out += "\n";
      }
      out += pad + e.key + "\n";
      if (e.value.kind() == Value::Kind::List) {
        out += format_value(e.value, indent) + ";\n";
      } else {
        out += format_value(e.value, indent) + "\n";
      }
      if (indent == 0) out += "\n";
    } else {
      std::string key = e.key;
      const int padding = key_column - static_cast<int>(key.size());
      key += std::string(static_cast<std::size_t>(padding > 0 ? padding : 1), ' ');
      out += pad + key + format_value(e.value, indent) + ";\n";
    }
  }
  return out;
}

// ------------------------------------------------------------------------------------------ format

std::string format_number(double x) {
  if (!std::isfinite(x)) {
    throw std::invalid_argument("foam: cannot write a non-finite number to an OpenFOAM dictionary");
  }
  if (x == 0.0) return "0";
  // A whole number as an integer: OpenFOAM reads a cell count (a label) "1e+05" as an error.
  if (std::abs(x) < 1e15 && x == std::round(x)) return std::to_string(static_cast<long long>(x));
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, x);
  if (result.ec != std::errc{}) throw std::runtime_error("foam: number formatting failed");
  return std::string(buffer, result.ptr);
}

std::string format_value(const Value& v, int indent) {
  const std::string pad = indentation(indent);
  switch (v.kind()) {
    case Value::Kind::Word:
      return v.text();
    case Value::Kind::String: {
      // (built step by step: GCC 12 warns falsely on "literal" + std::string&&)
      std::string quoted(1, '"');
      quoted += escape_string(v.text());
      quoted += '"';
      return quoted;
    }
    case Value::Kind::Number:
      return format_number(v.number());
    case Value::Kind::Sequence: {
      std::string out;
      for (const Value& t : v.items()) {
        if (!out.empty()) out += ' ';
        out += format_value(t, indent);
      }
      return out;
    }
    case Value::Kind::List: {
      if (list_is_inline(v)) {
        std::string out = "(";
        for (std::size_t i = 0; i < v.items().size(); ++i) {
          if (i > 0) out += ' ';
          out += format_value(v.items()[i], indent);
        }
        return out + ")";
      }
      std::string out = pad + "(\n";
      for (const Value& item : v.items()) {
        if (is_block(item)) {
          out += format_value(item, indent + 1) + "\n";
        } else {
          out += indentation(indent + 1) + format_value(item, indent + 1) + "\n";
        }
      }
      return out + pad + ")";
    }
    case Value::Kind::Dict:
      return pad + "{\n" + v.dict().format(indent + 1) + pad + "}";
    case Value::Kind::NamedDict:
      return pad + v.text() + "\n" + pad + "{\n" + v.dict().format(indent + 1) + pad + "}";
  }
  return {};
}

std::string format_file(const FileHeader& header, const Dictionary& body) {
  std::string out =
      "/*--------------------------------*- C++ -*----------------------------------*\\\n"
      "  =========                 |\n"
      "  \\\\      /  F ield         | OpenFOAM: The Open Source CFD Toolbox\n"
      "   \\\\    /   O peration     | Version:  v1912\n"
      "    \\\\  /    A nd           | Written by hydrojump from the study spec\n"
      "     \\\\/     M anipulation  |\n"
      "\\*---------------------------------------------------------------------------*/\n";
  Dictionary foam_file;
  foam_file.set("version", word("2.0"));
  foam_file.set("format", word("ascii"));
  foam_file.set("class", word(header.class_name));
  if (!header.location.empty()) foam_file.set("location", string(header.location));
  foam_file.set("object", word(header.object));
  Dictionary top;
  top.set("FoamFile", foam_file);
  out += top.format(0);
  out += "// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //\n\n";
  out += body.format(0);
  out += "\n// ************************************************************************* //\n";
  return out;
}

}  // namespace hydrojump::reference::foam
