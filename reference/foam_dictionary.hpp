// OpenFOAM dictionary files written from C++: values, nested dictionaries, lists, dimension sets and
// the FoamFile header, formatted the way OpenFOAM's own tutorials are (keys padded to 16 columns,
// 4-space indentation, one entry per line, `;` after every keyword entry).
//
// Usage
//   foam::Dictionary d;
//   d.set("application", foam::word("interFoam"));
//   d.set("endTime", 10.0);
//   d.set("maxCo", 0.8);
//   foam::Dictionary& inlet = d.subdict("boundaryField").subdict("inlet");
//   inlet.set("type", foam::word("fixedValue"));
//   inlet.set("value", foam::uniform(foam::vector(2.0, 0.0, 0.0)));
//   std::string text = foam::format_file(foam::FileHeader{"volVectorField", "0", "U"}, d);
//
// gives
//   application     interFoam;
//   endTime         10;
//   maxCo           0.8;
//   boundaryField
//   {
//       inlet
//       {
//           type            fixedValue;
//           value           uniform (2 0 0);
//       }
//   }
//
// Numbers are written with the shortest representation that reads back to the same double (so every
// value in a generated case is exactly the one computed from the spec); non-finite numbers are
// rejected with std::invalid_argument, because OpenFOAM cannot read them.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace hydrojump::reference::foam {

class Dictionary;

// One value of a dictionary entry or list item.
class Value {
 public:
  enum class Kind { Word, String, Number, Sequence, List, Dict, NamedDict };

  Value(double number);                           // NOLINT: implicit on purpose (d.set("k", 1.5))
  Value(int number);                              // NOLINT
  Value(const Dictionary& dict);                  // NOLINT: a nested dictionary

  Kind kind() const { return kind_; }
  const std::string& text() const { return text_; }        // Word, String, NamedDict name
  double number() const { return number_; }
  const std::vector<Value>& items() const { return items_; }  // Sequence, List
  const Dictionary& dict() const;                            // Dict, NamedDict

  // Factories (see the free functions below for the usual spelling).
  static Value make_word(std::string token);
  static Value make_string(std::string text);
  static Value make_sequence(std::vector<Value> tokens);
  static Value make_list(std::vector<Value> items);
  static Value make_named_dict(std::string name, const Dictionary& dict);

 private:
  Value() = default;
  Kind kind_ = Kind::Word;
  std::string text_;
  double number_ = 0.0;
  std::vector<Value> items_;
  std::shared_ptr<Dictionary> dict_;
  friend class Dictionary;
};

// A bare token (or several space-separated tokens written verbatim): Euler, Gauss linear, on.
Value word(std::string token);
// A double-quoted string, e.g. a location or a file name: "constant".
Value string(std::string text);
// Several values on one line separated by spaces: `uniform 0`, `[0 1 -1 0 0 0 0] 9.81`.
Value sequence(std::vector<Value> tokens);
// A parenthesised list: `(water air)`; dictionaries inside are written one per line.
Value list(std::vector<Value> items);
// A list item made of a keyword and a dictionary: `boxToCell { ... }` in setFieldsDict regions.
Value named_dict(std::string name, const Dictionary& dict);
// `(x y z)`.
Value vector(double x, double y, double z);
// `uniform v` for field values.
Value uniform(const Value& v);
// A dimension set `[kg m s K mol A cd]`.
Value dimensions(const std::array<int, 7>& exponents);
// `on` / `off`.
Value on_off(bool on);
// `yes` / `no`.
Value yes_no(bool yes);

// An ordered dictionary. Keys keep their insertion order; setting an existing key replaces its value
// in place. Keys are written verbatim, so regular-expression keys must be given with their quotes:
// `"alpha.water.*"`.
class Dictionary {
 public:
  Dictionary& set(const std::string& key, const Value& value);
  // The nested dictionary called `key`, created empty if absent. Throws std::logic_error if `key`
  // holds something else.
  Dictionary& subdict(const std::string& key);
  // A directive or raw line written as is, in order with the entries (e.g. `#include "x"`).
  Dictionary& directive(const std::string& line);

  bool contains(const std::string& key) const;
  // The value of `key`; throws std::out_of_range naming the key if absent.
  const Value& at(const std::string& key) const;
  const Dictionary& subdict_at(const std::string& key) const;
  std::vector<std::string> keys() const;
  bool empty() const { return entries_.empty(); }

  // The entries formatted at indentation level `indent` (4 spaces each), without braces.
  std::string format(int indent = 0) const;

 private:
  struct Entry {
    std::string key;       // empty for a directive
    Value value;
    std::string directive;
  };
  std::vector<Entry> entries_;
};

// Formats a double with the shortest text that reads back exactly; -0 is written as 0.
// Throws std::invalid_argument for NaN and infinities.
std::string format_number(double x);

// Formats one value (no trailing `;`) at indentation level `indent`.
std::string format_value(const Value& v, int indent = 0);

// The FoamFile header of a file.
struct FileHeader {
  std::string class_name;   // dictionary, volScalarField, volVectorField, uniformDimensionedVectorField
  std::string location;     // "system", "constant", "0" (empty: omitted)
  std::string object;       // file name
};

// The complete text of an OpenFOAM file: banner, FoamFile header, entries, closing rule.
std::string format_file(const FileHeader& header, const Dictionary& body);

}  // namespace hydrojump::reference::foam
