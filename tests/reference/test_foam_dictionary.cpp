// The OpenFOAM dictionary writer: formatting of values, nesting, lists, numbers and the file header.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>

#include "reference/foam_dictionary.hpp"

namespace foam = hydrojump::reference::foam;

TEST_CASE("numbers are written so they read back exactly", "[reference][foam_dictionary]") {
  CHECK(foam::format_number(0.0) == "0");
  CHECK(foam::format_number(-0.0) == "0");
  CHECK(foam::format_number(2.0) == "2");
  CHECK(foam::format_number(0.0254) == "0.0254");
  CHECK(foam::format_number(1.0e-6) == "1e-06");
  CHECK(foam::format_number(-9.81) == "-9.81");
  // Whole numbers as integers: a cell count "1e+05" is not a label to OpenFOAM.
  CHECK(foam::format_number(100000.0) == "100000");
  CHECK(foam::Value(100000).number() == 100000.0);
  CHECK(foam::format_number(3.0e9) == "3000000000");
  CHECK(foam::format_number(-2.0e6) == "-2000000");
  for (double x : {0.1 + 0.2, 1.0 / 3.0, 6.02214076e23, 1.0e-300, -2.5e-7}) {
    const std::string text = foam::format_number(x);
    CHECK(std::strtod(text.c_str(), nullptr) == x);
  }
  CHECK_THROWS_AS(foam::format_number(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
  CHECK_THROWS_AS(foam::format_number(std::numeric_limits<double>::infinity()), std::invalid_argument);
  CHECK_THROWS_AS(foam::Value(std::numeric_limits<double>::infinity()), std::invalid_argument);
}

TEST_CASE("scalar entries are padded to column 16 and end with a semicolon",
          "[reference][foam_dictionary]") {
  foam::Dictionary d;
  d.set("application", foam::word("interFoam"));
  d.set("endTime", 10.0);
  d.set("a_very_long_keyword_name", 1);
  d.set("location", foam::string("constant"));
  d.set("internalField", foam::uniform(foam::vector(2.0, 0.0, -0.5)));
  d.set("dimensions", foam::dimensions({0, 1, -1, 0, 0, 0, 0}));
  CHECK(d.format() ==
        "application     interFoam;\n"
        "endTime         10;\n"
        "a_very_long_keyword_name 1;\n"
        "location        \"constant\";\n"
        "internalField   uniform (2 0 -0.5);\n"
        "dimensions      [0 1 -1 0 0 0 0];\n");
}

TEST_CASE("setting an existing key replaces it in place", "[reference][foam_dictionary]") {
  foam::Dictionary d;
  d.set("a", 1).set("b", 2).set("a", 3);
  CHECK(d.keys() == std::vector<std::string>{"a", "b"});
  CHECK(d.at("a").number() == 3.0);
  CHECK_THROWS_AS(d.at("missing"), std::out_of_range);
  CHECK_THROWS_AS(d.subdict("a"), std::logic_error);
}

TEST_CASE("nested dictionaries are indented by four spaces", "[reference][foam_dictionary]") {
  foam::Dictionary d;
  foam::Dictionary& inlet = d.subdict("boundaryField").subdict("inlet");
  inlet.set("type", foam::word("fixedValue"));
  inlet.set("value", foam::uniform(1));
  d.subdict("boundaryField").subdict("\"(walls|bed)\"").set("type", foam::word("zeroGradient"));
  CHECK(d.format() ==
        "boundaryField\n"
        "{\n"
        "    inlet\n"
        "    {\n"
        "        type            fixedValue;\n"
        "        value           uniform 1;\n"
        "    }\n"
        "    \"(walls|bed)\"\n"
        "    {\n"
        "        type            zeroGradient;\n"
        "    }\n"
        "}\n"
        "\n");
  CHECK(d.subdict_at("boundaryField").subdict_at("inlet").at("type").text() == "fixedValue");
}

TEST_CASE("a copied dictionary value is independent of later edits", "[reference][foam_dictionary]") {
  foam::Dictionary inner;
  inner.set("x", 1);
  foam::Dictionary a;
  a.set("inner", inner);
  foam::Dictionary b = a;
  b.subdict("inner").set("x", 2);
  CHECK(a.subdict_at("inner").at("x").number() == 1.0);
  CHECK(b.subdict_at("inner").at("x").number() == 2.0);
}

TEST_CASE("short lists are inline, lists of dictionaries are one item per line",
          "[reference][foam_dictionary]") {
  foam::Dictionary d;
  d.set("phases", foam::list({foam::word("water"), foam::word("air")}));
  foam::Dictionary box;
  box.set("box", foam::sequence({foam::vector(0, 0, -1), foam::vector(1, 0.5, 1)}));
  box.set("fieldValues", foam::list({foam::word("volScalarFieldValue alpha.water 1")}));
  d.set("regions", foam::list({foam::named_dict("boxToCell", box)}));
  CHECK(d.format() ==
        "phases          (water air);\n"
        "\n"
        "regions\n"
        "(\n"
        "    boxToCell\n"
        "    {\n"
        "        box             (0 0 -1) (1 0.5 1);\n"
        "        fieldValues     (volScalarFieldValue alpha.water 1);\n"
        "    }\n"
        ");\n"
        "\n");
}

TEST_CASE("long lists are split one item per line", "[reference][foam_dictionary]") {
  std::vector<foam::Value> points;
  for (int i = 0; i < 20; ++i) points.push_back(foam::vector(i * 0.125, 0.5, 0.0));
  foam::Dictionary d;
  d.set("vertices", foam::list(points));
  const std::string text = d.format();
  CHECK(text.rfind("vertices\n(\n    (0 0.5 0)\n    (0.125 0.5 0)\n", 0) == 0);
  CHECK(text.find("    (2.375 0.5 0)\n);\n") != std::string::npos);
}

TEST_CASE("directives are kept in order", "[reference][foam_dictionary]") {
  foam::Dictionary d;
  d.set("a", 1);
  d.directive("#includeEtc \"caseDicts/setConstraintTypes\"");
  d.set("b", 2);
  CHECK(d.format() == "a               1;\n#includeEtc \"caseDicts/setConstraintTypes\"\nb               2;\n");
}

TEST_CASE("files carry the FoamFile header", "[reference][foam_dictionary]") {
  foam::Dictionary body;
  body.set("dimensions", foam::dimensions({0, 1, -2, 0, 0, 0, 0}));
  body.set("value", foam::vector(0, -9.81, 0));
  const std::string text =
      foam::format_file(foam::FileHeader{"uniformDimensionedVectorField", "constant", "g"}, body);
  CHECK(text.find("FoamFile\n{\n    version         2.0;\n    format          ascii;\n"
                  "    class           uniformDimensionedVectorField;\n"
                  "    location        \"constant\";\n    object          g;\n}\n") != std::string::npos);
  CHECK(text.find("value           (0 -9.81 0);\n") != std::string::npos);
  CHECK(text.rfind("/*", 0) == 0);
}
