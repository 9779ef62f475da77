// tests/compiler/diagnostics_test.cpp: golden diagnostics of the compiler (checking and
// lowering: compiler/lower*.cpp, compiler/builtins.cpp). Each check compiles a small shader and
// requires the exact, complete text: file:line:col, severity, message, the source line and the
// caret, and any note. The "Regression tests" at the end guard bugs this suite found.
//
// Distinct kinds of diagnostics checked here (compile_test.cpp and lang/parse_test.cpp check
// more, mostly syntax):
//   control flow     1 'break' outside of a loop            2 'continue' outside of a loop
//                    3 'break N'/'continue N' is inside only M loops
//                    4 this loop runs more than 10000 iterations
//   conditions       5 a condition must be a comparison or a float
//   operators        6 invalid operands to '<' ...: only floats are ordered
//                    7 ... a color does not compare with a point, vector or normal
//                    8 ... strings compare only with == and != to strings
//                    9 ... '&&' combines conditions      10 invalid operands to '+' (string and float)
//                   11 ... a color does not combine with a point, vector or normal
//                   12 ... '^' is the cross product of two vectors
//                   13 invalid operand to unary '-'      14 a triple's components must be floats
//                   15 invalid operands to '+=' (compound assignment)
//   ?:              16 the two results of '?:' have incompatible types
//                   17 a string cannot depend on a condition that varies over the surface
//   user functions  18 'f' expects N arguments, got M (+ note)
//                   19 argument N of 'f' must be a variable (its parameter is output)
//                   20 cannot pass 'u' to output parameter 'y': it is read-only
//                   21 argument N of 'f' is X; the parameter 'p' is Y (output or array mismatch)
//                   22 cannot assign a point to parameter 'x' of 'f'
//                   23 argument N of 'f' must be an array variable
//                   24 unknown function (also a nested function out of its scope)
//                   25 recursive call to 'f' (direct and mutual; + note)
//                   26 calls nest deeper than 64 functions
//                   27 a void function does not return a value
//                   28 a shader does not return a value
//                   29 'return' needs a value in a function returning float
//                   30 function 'f' returns a float but has no 'return' with a value
//                   31 cannot assign a string to the return value
//                   32 redefinition of function 'f' (+ note)
//                   33 extern variable 'k' is not declared in an enclosing scope
//                   34 extern variable 'k' is declared a point here but is a float
//   spaces          35 unknown coordinate space           36 coordinate space '...' is projective
//                   37 expected the name of a coordinate space
//                   38 'transform' expects 2 or 3 arguments
//                   39 'transform' transforms a point, vector or normal, not ...
//                   40 unknown color space 'hsb'
//   arrays          41 index N is outside the array (size M)   42 only an array can be indexed
//                   43 unknown identifier                 44 array 'a' needs a size
//                   45 cannot assign to the whole array   46 'x' is not an array
//                   47 an array index must be a float     48 string arrays are not supported yet
//   unsupported     49 function 'environment' is not supported yet
//                   50 matrix values are not supported yet 51 matrix variables are not supported yet
//                   52 surface shaders are not supported yet
//   built-ins       53 no version of 'min' takes (...); expected ...
//                   54 'sqrt' expects 1 argument, got 2 (also 'comp')
//                   55 the new component of 'setxcomp' must be a float
//                   56 the first argument of 'setycomp' must be a variable
//                   57 cannot assign to 'Ng': it is a read-only global
//                   58 'spline' expects a float parameter and at least 4 knots
//                   59 spline knots must all be floats or all triples
//                   60 unknown spline basis '...' (also: a bezier spline takes 4 + 3n knots)
//                   61 no version of 'noise' takes (...)   62 no version of 'pnoise' takes (...)
//                   63 unknown filterstep parameter       64 filterstep's optional arguments are pairs
//                   65 'filterstep' expects (float edge, float x) or (float edge, float x0, float x1)
//   variables       66 assignment to undeclared variable  67 cannot assign to 'mode': it is read-only
//                   68 cannot assign a string to float variable 'x'
//                   69 variable 'q' is used before it is assigned a value (a warning)
//                   70 cannot cast a point to float (and a string to point)
//   parameters      71 redefinition of parameter          72 default value of string parameter
//                   73 parameter 'k' needs a default value
//                   74 only one shader per file is supported
//   warnings        75 unused variable                    76 shader 't' never changes P or N
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "tests/test_util.h"

using namespace affray;

namespace {

/// The diagnostics of `source`, which must not compile.
std::string Diagnose(const std::string& source) {
    compiler::CompileResult r = compiler::CompileSource("test.sl", source);
    CHECK_FALSE(r.ok());
    return r.diagnostics.format();
}

/// The diagnostics (warnings) of `source`, which must compile.
std::string Warnings(const std::string& source) {
    compiler::CompileResult r = compiler::CompileSource("test.sl", source);
    INFO(r.diagnostics);
    CHECK(r.ok());
    return r.diagnostics.format();
}

}  // namespace

TEST_CASE("break and continue outside their loops", "[compiler][diagnostics]") {
    CHECK(Diagnose("displacement t() {\n  P += 1;\n  break;\n}\n") ==
          "test.sl:3:3: error: 'break' outside of a loop\n"
          "      break;\n"
          "      ^\n");
    CHECK(Diagnose("displacement t() {\n  if (u > 0) continue;\n}\n") ==
          "test.sl:2:14: error: 'continue' outside of a loop\n"
          "      if (u > 0) continue;\n"
          "                 ^\n");
    CHECK(Diagnose("displacement t() {\n  float i;\n  for (i = 0; i < 1; i += 1) break 2;\n}\n") ==
          "test.sl:3:30: error: 'break 2' is inside only 1 loop\n"
          "      for (i = 0; i < 1; i += 1) break 2;\n"
          "                                 ^\n");
    CHECK(Diagnose("displacement t() {\n  float i, j;\n  for (i = 0; i < 1; i += 1)\n      for (j = 0; j < 1; j += 1) "
                   "continue 3;\n}\n") ==
          "test.sl:4:34: error: 'continue 3' is inside only 2 loops\n"
          "          for (j = 0; j < 1; j += 1) continue 3;\n"
          "                                     ^\n");
}

TEST_CASE("a loop that never ends", "[compiler][diagnostics]") {
    // The condition is constant: the unrolling would never stop.
    CHECK(Diagnose("displacement t() {\n  float i = 0;\n  while (i < 1) P += 0;\n}\n") ==
          "test.sl:3:3: error: this loop runs more than 10000 iterations: affray unrolls loops; is its condition ever "
          "false? (limit loop-iterations = 10000; raise it with --limit loop-iterations=N)\n"
          "      while (i < 1) P += 0;\n"
          "      ^\n");
}

// Found by fuzz_sl (fuzz/regressions/fuzz_sl/nested_endless_loop.sl, a timeout): a loop that
// never ends, inside other loops, was unrolled to its budget again for every iteration of the
// loops around it (nine budgets here, minutes under AddressSanitizer). It is reported once and
// unrolled once.
TEST_CASE("a loop that never ends inside other loops is unrolled to its budget once", "[compiler][diagnostics]") {
    // One budget of this loop asks for about 100000 operations, under the program-ops limit
    // (250000); nine would pass it, and the error would be that limit's instead.
    const std::string alone = Diagnose("displacement t() {\n  float k;\n  for (k = 0; k < 1; k += 0) P += 0;\n}\n");
    const std::string nested = Diagnose(
        "displacement t() {\n  float i, j, k;\n  for (i = 0; i < 3; i += 1)\n"
        "    for (j = 0; j < 3; j += 1)\n      for (k = 0; k < 1; k += 0) P += 0;\n}\n");
    CHECK(alone.find("test.sl:3:3: error: this loop runs more than 10000 iterations") == 0);
    CHECK(nested.find("test.sl:5:7: error: this loop runs more than 10000 iterations") == 0);
    CHECK(std::count(nested.begin(), nested.end(), '^') == 1);
    CHECK(nested.find("grows past") == std::string::npos);
}

TEST_CASE("conditions of the wrong type", "[compiler][diagnostics]") {
    CHECK(Diagnose("displacement t() {\n  if (P) P += 1;\n}\n") ==
          "test.sl:2:7: error: a condition must be a comparison or a float, not a point\n"
          "      if (P) P += 1;\n"
          "          ^\n");
    CHECK(Diagnose("displacement t() {\n  while (\"yes\") P += 1;\n}\n") ==
          "test.sl:2:10: error: a condition must be a comparison or a float, not a string\n"
          "      while (\"yes\") P += 1;\n"
          "             ^\n");
    CHECK(Diagnose("displacement t() {\n  P += P ? 1 : 2;\n}\n") ==
          "test.sl:2:8: error: a condition must be a comparison or a float, not a point\n"
          "      P += P ? 1 : 2;\n"
          "           ^\n");
    CHECK(Diagnose("displacement t() {\n  P += !P;\n}\n") ==
          "test.sl:2:9: error: a condition must be a comparison or a float, not a point\n"
          "      P += !P;\n"
          "            ^\n");
}

TEST_CASE("invalid operands to comparisons and logical operators", "[compiler][diagnostics]") {
    CHECK(Diagnose("displacement t() {\n  if (P < point(1, 1, 1)) P += 1;\n}\n") ==
          "test.sl:2:9: error: invalid operands to '<' (point and point): only floats are ordered\n"
          "      if (P < point(1, 1, 1)) P += 1;\n"
          "            ^\n");
    CHECK(Diagnose("displacement t() {\n  if (P == color(1, 1, 1)) P += 1;\n}\n") ==
          "test.sl:2:9: error: invalid operands to '==' (point and color): a color does not compare with a point, "
          "vector or normal\n"
          "      if (P == color(1, 1, 1)) P += 1;\n"
          "            ^\n");
    CHECK(Diagnose("displacement t() {\n  if (\"a\" < \"b\") P += 1;\n}\n") ==
          "test.sl:2:11: error: invalid operands to '<' (string and string): strings compare only with == and != to "
          "strings\n"
          "      if (\"a\" < \"b\") P += 1;\n"
          "              ^\n");
    CHECK(Diagnose("displacement t() {\n  if (\"a\" == 1) P += 1;\n}\n") ==
          "test.sl:2:11: error: invalid operands to '==' (string and float): strings compare only with == and != to "
          "strings\n"
          "      if (\"a\" == 1) P += 1;\n"
          "              ^\n");
    CHECK(Diagnose("displacement t() {\n  if (P && 1) P += 1;\n}\n") ==
          "test.sl:2:9: error: invalid operands to '&&' (point and float): '&&' combines conditions\n"
          "      if (P && 1) P += 1;\n"
          "            ^\n");
}

TEST_CASE("invalid operands to arithmetic", "[compiler][diagnostics]") {
    CHECK(Diagnose("displacement t() {\n  P += \"a\" + 1;\n}\n") ==
          "test.sl:2:12: error: invalid operands to '+' (string and float)\n"
          "      P += \"a\" + 1;\n"
          "               ^\n");
    CHECK(Diagnose("displacement t() {\n  P += color(1, 0, 0) + P;\n}\n") ==
          "test.sl:2:23: error: invalid operands to '+' (color and point): a color does not combine with a point, "
          "vector or normal\n"
          "      P += color(1, 0, 0) + P;\n"
          "                          ^\n");
    CHECK(Diagnose("displacement t() {\n  P = P ^ 1;\n}\n") ==
          "test.sl:2:9: error: invalid operands to '^' (point and float): '^' is the cross product of two vectors\n"
          "      P = P ^ 1;\n"
          "            ^\n");
    // Two colors are triples but not spatial: no cross product either.
    CHECK(Diagnose("displacement t() {\n  vector v = color(1, 0, 0) ^ color(0, 1, 0);\n}\n") ==
          "test.sl:2:29: error: invalid operands to '^' (color and color): '^' is the cross product of two vectors\n"
          "      vector v = color(1, 0, 0) ^ color(0, 1, 0);\n"
          "                                ^\n");
    CHECK(Diagnose("displacement t() {\n  P += -\"a\";\n}\n") ==
          "test.sl:2:8: error: invalid operand to unary '-' (string)\n"
          "      P += -\"a\";\n"
          "           ^\n");
    CHECK(Diagnose("displacement t() {\n  P = (1, \"a\", 2);\n}\n") ==
          "test.sl:2:11: error: a triple's components must be floats, got a string\n"
          "      P = (1, \"a\", 2);\n"
          "              ^\n");
    CHECK(Diagnose("displacement t() {\n  string s = \"a\";\n  s += 1;\n}\n") ==
          "test.sl:3:5: error: invalid operands to '+=' (string and float)\n"
          "      s += 1;\n"
          "        ^\n");
}

TEST_CASE("incompatible or varying results of ?:", "[compiler][diagnostics]") {
    CHECK(Diagnose("displacement t() {\n  P += u > 0.5 ? P : color(1, 0, 0);\n}\n") ==
          "test.sl:2:16: error: the two results of '?:' have incompatible types (point and color)\n"
          "      P += u > 0.5 ? P : color(1, 0, 0);\n"
          "                   ^\n");
    CHECK(Diagnose("displacement t() {\n  P += u > 0.5 ? 1 : \"a\";\n}\n") ==
          "test.sl:2:16: error: the two results of '?:' have incompatible types (float and string)\n"
          "      P += u > 0.5 ? 1 : \"a\";\n"
          "                   ^\n");
}

TEST_CASE("calls to user functions", "[compiler][diagnostics]") {
    CHECK(Diagnose("float f(float x) { return x; }\ndisplacement t() {\n  P += f(1, 2);\n}\n") ==
          "test.sl:3:8: error: 'f' expects 1 argument, got 2\n"
          "      P += f(1, 2);\n"
          "           ^\n"
          "test.sl:1:7: note: 'f' is defined here\n"
          "    float f(float x) { return x; }\n"
          "          ^\n");
    CHECK(Diagnose("void f(float x, y) { }\ndisplacement t() {\n  f();\n}\n") ==
          "test.sl:3:3: error: 'f' expects 2 arguments, got 0\n"
          "      f();\n"
          "      ^\n"
          "test.sl:1:6: note: 'f' is defined here\n"
          "    void f(float x, y) { }\n"
          "         ^\n");
    CHECK(Diagnose("void dbl(float x; output float y) { y = 2 * x; }\ndisplacement t() {\n  float r = 0;\n  dbl(1, r + "
                   "1);\n}\n") ==
          "test.sl:4:12: error: argument 2 of 'dbl' must be a variable (its parameter is output)\n"
          "      dbl(1, r + 1);\n"
          "               ^\n");
    CHECK(Diagnose("void dbl(float x; output float y) { y = 2 * x; }\ndisplacement t() {\n  dbl(1, u);\n}\n") ==
          "test.sl:3:10: error: cannot pass 'u' to output parameter 'y': it is read-only\n"
          "      dbl(1, u);\n"
          "             ^\n");
    CHECK(Diagnose("void f(output float y) { y = 1; }\ndisplacement t() {\n  f(P);\n}\n") ==
          "test.sl:3:5: error: argument 1 of 'f' is a point; the parameter 'y' is a float (output)\n"
          "      f(P);\n"
          "        ^\n");
    CHECK(Diagnose("float f(float x) { return x; }\ndisplacement t() {\n  P += f(P);\n}\n") ==
          "test.sl:3:10: error: cannot assign a point to parameter 'x' of 'f'\n"
          "      P += f(P);\n"
          "             ^\n");
    CHECK(Diagnose("float sum(float a[]) { return a[0]; }\ndisplacement t() {\n  P += sum(1);\n}\n") ==
          "test.sl:3:12: error: argument 1 of 'sum' must be an array variable\n"
          "      P += sum(1);\n"
          "               ^\n");
    CHECK(Diagnose("float sum(float a[]) { return a[0]; }\ndisplacement t() {\n  float x = 1;\n  P += sum(x);\n}\n") ==
          "test.sl:4:12: error: argument 1 of 'sum' is a float; the parameter 'a' is a float array\n"
          "      P += sum(x);\n"
          "               ^\n");
    // A function defined in a block is not visible after it.
    CHECK(Diagnose("displacement t() {\n  { float g() { return 1; } }\n  P += g();\n}\n") ==
          "test.sl:3:8: error: unknown function 'g'\n"
          "      P += g();\n"
          "           ^\n");
}

TEST_CASE("recursion, direct and mutual, and calls nested too deep", "[compiler][diagnostics]") {
    CHECK(Diagnose("void f(float x) {\n  f(x);\n}\ndisplacement t() {\n  f(1);\n}\n") ==
          "test.sl:2:3: error: recursive call to 'f': affray inlines functions, so a function cannot call itself\n"
          "      f(x);\n"
          "      ^\n"
          "test.sl:1:6: note: 'f' is defined here\n"
          "    void f(float x) {\n"
          "         ^\n");
    // f -> g -> f: reported where the cycle closes.
    CHECK(Diagnose("void f() {\n  g();\n}\nvoid g() {\n  f();\n}\ndisplacement t() {\n  f();\n}\n") ==
          "test.sl:5:3: error: recursive call to 'f': affray inlines functions, so a function cannot call itself\n"
          "      f();\n"
          "      ^\n"
          "test.sl:1:6: note: 'f' is defined here\n"
          "    void f() {\n"
          "         ^\n");
}

TEST_CASE("return values", "[compiler][diagnostics]") {
    CHECK(Diagnose("void f() {\n  return 1;\n}\ndisplacement t() {\n  f();\n}\n") ==
          "test.sl:2:3: error: a void function does not return a value\n"
          "      return 1;\n"
          "      ^\n");
    CHECK(Diagnose("displacement t() {\n  return 1;\n}\n") ==
          "test.sl:2:3: error: a shader does not return a value\n"
          "      return 1;\n"
          "      ^\n");
    CHECK(Diagnose("float f(float x) {\n  if (x > 0) return;\n  return x;\n}\ndisplacement t() {\n  P += f(u);\n}\n") ==
          "test.sl:2:14: error: 'return' needs a value in a function returning float\n"
          "      if (x > 0) return;\n"
          "                 ^\n");
    CHECK(Diagnose("float f(float x) {\n  x += 1;\n}\ndisplacement t() {\n  P += f(1);\n}\n") ==
          "test.sl:1:7: error: function 'f' returns a float but has no 'return' with a value\n"
          "    float f(float x) {\n"
          "          ^\n");
    CHECK(Diagnose("float f() {\n  if (u > 0) return \"a\";\n  return 1;\n}\ndisplacement t() {\n  P += f();\n}\n") ==
          "test.sl:2:21: error: cannot assign a string to the return value\n"
          "      if (u > 0) return \"a\";\n"
          "                        ^\n");
}

TEST_CASE("redefinition of a function", "[compiler][diagnostics]") {
    CHECK(Diagnose("float f() { return 1; }\nfloat f() { return 2; }\ndisplacement t() {\n  P += f();\n}\n") ==
          "test.sl:2:7: error: redefinition of function 'f'\n"
          "    float f() { return 2; }\n"
          "          ^\n"
          "test.sl:1:7: note: 'f' was defined here\n"
          "    float f() { return 1; }\n"
          "          ^\n");
    CHECK(Diagnose("displacement t() {\n  float g() { return 1; }\n  float g() { return 2; }\n  P += g();\n}\n") ==
          "test.sl:3:9: error: redefinition of function 'g'\n"
          "      float g() { return 2; }\n"
          "            ^\n"
          "test.sl:2:9: note: 'g' was defined here\n"
          "      float g() { return 1; }\n"
          "            ^\n");
}

TEST_CASE("extern of an undeclared variable, or of another type", "[compiler][diagnostics]") {
    CHECK(Diagnose("void f() {\n  extern float k;\n}\ndisplacement t() {\n  f();\n}\n") ==
          "test.sl:2:16: error: extern variable 'k' is not declared in an enclosing scope\n"
          "      extern float k;\n"
          "                   ^\n");
    CHECK(Diagnose("displacement t() {\n  extern float k;\n}\n") ==
          "test.sl:2:16: error: extern variable 'k' is not declared in an enclosing scope\n"
          "      extern float k;\n"
          "                   ^\n");
    CHECK(Diagnose("displacement t() {\n  float k = 1;\n  void f() { extern point k; }\n  f();\n}\n") ==
          "test.sl:3:27: error: extern variable 'k' is declared a point here but is a float\n"
          "      void f() { extern point k; }\n"
          "                              ^\n");
}

TEST_CASE("coordinate spaces", "[compiler][diagnostics]") {
    CHECK(Diagnose("displacement t() {\n  P = transform(\"wrold\", P);\n}\n") ==
          "test.sl:2:17: error: unknown coordinate space 'wrold'\n"
          "      P = transform(\"wrold\", P);\n"
          "                    ^\n");
    CHECK(Diagnose("displacement t() {\n  P = transform(\"NDC\", P);\n}\n") ==
          "test.sl:2:17: error: coordinate space 'NDC' is projective and not supported\n"
          "      P = transform(\"NDC\", P);\n"
          "                    ^\n");
    CHECK(Diagnose("displacement t() {\n  P = point \"raster\" (1, 2, 3);\n}\n") ==
          "test.sl:2:7: error: coordinate space 'raster' is projective and not supported\n"
          "      P = point \"raster\" (1, 2, 3);\n"
          "          ^\n");
    CHECK(Diagnose("displacement t() {\n  P = transform(1, P);\n}\n") ==
          "test.sl:2:17: error: expected the name of a coordinate space, got a float\n"
          "      P = transform(1, P);\n"
          "                    ^\n");
    CHECK(Diagnose("displacement t() {\n  P = transform(P);\n}\n") ==
          "test.sl:2:7: error: 'transform' expects 2 or 3 arguments, got 1\n"
          "      P = transform(P);\n"
          "          ^\n");
    CHECK(Diagnose("displacement t() {\n  P = transform(\"world\", color(1, 0, 0));\n}\n") ==
          "test.sl:2:26: error: 'transform' transforms a point, vector or normal, not a color\n"
          "      P = transform(\"world\", color(1, 0, 0));\n"
          "                             ^\n");
    CHECK(Diagnose("displacement t() {\n  color c = color \"hsb\" (1, 0, 0);\n}\n") ==
          "test.sl:2:13: error: unknown color space 'hsb' (rgb, hsv, hsl, xyz, XYZ, xyY and YIQ are known)\n"
          "      color c = color \"hsb\" (1, 0, 0);\n"
          "                ^\n");
}

TEST_CASE("arrays", "[compiler][diagnostics]") {
    CHECK(Diagnose("displacement t() {\n  float a[3] = {1, 2, 3};\n  P += a[3];\n}\n") ==
          "test.sl:3:10: error: index 3 is outside the array (size 3)\n"
          "      P += a[3];\n"
          "             ^\n");
    CHECK(Diagnose("displacement t() {\n  float a[3] = {1, 2, 3};\n  a[-1] = 0;\n}\n") ==
          "test.sl:3:5: error: index -1 is outside the array (size 3)\n"
          "      a[-1] = 0;\n"
          "        ^\n");
    CHECK(Diagnose("displacement t() {\n  float x = 1;\n  P += x[0];\n}\n") ==
          "test.sl:3:8: error: only an array can be indexed\n"
          "      P += x[0];\n"
          "           ^\n");
    CHECK(Diagnose("displacement t() {\n  P += y[0];\n}\n") ==
          "test.sl:2:8: error: unknown identifier 'y'\n"
          "      P += y[0];\n"
          "           ^\n");
    CHECK(Diagnose("displacement t() {\n  float a[];\n}\n") ==
          "test.sl:2:9: error: array 'a' needs a size (only function parameters and externs may omit it)\n"
          "      float a[];\n"
          "            ^\n");
    CHECK(Diagnose("displacement t() {\n  float a[2] = {1, 2};\n  a = 3;\n}\n") ==
          "test.sl:3:5: error: cannot assign to the whole array 'a'\n"
          "      a = 3;\n"
          "        ^\n");
    CHECK(Diagnose("displacement t() {\n  float x = 1;\n  x[0] = 3;\n}\n") ==
          "test.sl:3:8: error: 'x' is not an array\n"
          "      x[0] = 3;\n"
          "           ^\n");
    CHECK(Diagnose("displacement t() {\n  float a[2] = {1, 2};\n  P += a[P];\n}\n") ==
          "test.sl:3:10: error: an array index must be a float, not a point\n"
          "      P += a[P];\n"
          "             ^\n");
    CHECK(Diagnose("displacement t() {\n  string s[2] = {\"a\", \"b\"};\n}\n") ==
          "test.sl:2:10: error: string arrays are not supported yet\n"
          "      string s[2] = {\"a\", \"b\"};\n"
          "             ^\n");
}

TEST_CASE("unknown and unsupported functions and types", "[compiler][diagnostics]") {
    CHECK(Diagnose("displacement t() {\n  P += noize(P);\n}\n") ==
          "test.sl:2:8: error: unknown function 'noize'\n"
          "      P += noize(P);\n"
          "           ^\n");
    CHECK(Diagnose("displacement t() {\n  P += environment(\"x\", N);\n}\n") ==
          "test.sl:2:8: error: function 'environment' is not supported yet: affray reads texture() maps only\n"
          "      P += environment(\"x\", N);\n"
          "           ^\n");
    CHECK(Diagnose("imager t() {\n  P += 1;\n}\n") ==
          "test.sl:1:8: error: imager shaders are not supported yet; affray runs displacement, surface and light "
          "shaders\n"
          "    imager t() {\n"
          "           ^\n");
}

TEST_CASE("arguments of built-ins", "[compiler][diagnostics]") {
    CHECK(Diagnose("displacement t() {\n  P += min(\"a\", 1);\n}\n") ==
          "test.sl:2:8: error: no version of 'min' takes (string, float); expected (float or triple, float or triple) "
          "or (float or triple, float or triple, float or triple)\n"
          "      P += min(\"a\", 1);\n"
          "           ^\n");
    CHECK(Diagnose("displacement t() {\n  P += sqrt(1, 2);\n}\n") ==
          "test.sl:2:8: error: 'sqrt' expects 1 argument, got 2\n"
          "      P += sqrt(1, 2);\n"
          "           ^\n");
    CHECK(Diagnose("displacement t() {\n  P += comp(P, 1, 2);\n}\n") ==
          "test.sl:2:8: error: 'comp' expects 2 arguments, got 3\n"
          "      P += comp(P, 1, 2);\n"
          "           ^\n");
    CHECK(Diagnose("displacement t() {\n  setxcomp(P, N);\n}\n") ==
          "test.sl:2:15: error: the new component of 'setxcomp' must be a float, got a normal\n"
          "      setxcomp(P, N);\n"
          "                  ^\n");
    CHECK(Diagnose("displacement t() {\n  setycomp(P + 1, 2);\n}\n") ==
          "test.sl:2:14: error: the first argument of 'setycomp' must be a variable\n"
          "      setycomp(P + 1, 2);\n"
          "                 ^\n");
    CHECK(Diagnose("displacement t() {\n  setzcomp(Ng, 1);\n}\n") ==
          "test.sl:2:12: error: cannot assign to 'Ng': it is a read-only global\n"
          "      setzcomp(Ng, 1);\n"
          "               ^\n");
}

TEST_CASE("array parameters need constant initialiser lists", "[compiler][diagnostics]") {
    CHECK(Diagnose("displacement t(float w[2] = {1, u}) {\n  P += w[0];\n}\n") ==
          "test.sl:1:22: error: default value of parameter 'w' must be a constant expression\n"
          "    displacement t(float w[2] = {1, u}) {\n"
          "                         ^\n");
    CHECK(Diagnose("displacement t(float w[2]) {\n  P += w[0];\n}\n") ==
          "test.sl:1:22: error: array parameter 'w' needs a default value ({...})\n"
          "    displacement t(float w[2]) {\n"
          "                         ^\n");
    CHECK(Diagnose("displacement t(string w[2] = {\"a\", \"b\"}) {\n  P += 1;\n}\n") ==
          "test.sl:1:23: error: string arrays are not supported yet\n"
          "    displacement t(string w[2] = {\"a\", \"b\"}) {\n"
          "                          ^\n");
}

TEST_CASE("matrices: what they combine with", "[compiler][diagnostics]") {
    CHECK(Diagnose("displacement t() {\n  P = P * matrix 1;\n}\n") ==
          "test.sl:2:9: error: invalid operands to '*' (point and matrix): a matrix only multiplies or divides a "
          "matrix or a float (transform() applies it to a point)\n"
          "      P = P * matrix 1;\n"
          "            ^\n");
    CHECK(Diagnose("displacement t() {\n  matrix m = 1;\n  m += m;\n  P += determinant(m);\n}\n") ==
          "test.sl:3:5: error: invalid operands to '+=' (matrix and matrix)\n"
          "      m += m;\n"
          "        ^\n");
    CHECK(Diagnose("displacement t() {\n  matrix m = 1;\n  P += comp(m, 4, 0);\n}\n") ==
          "test.sl:3:16: error: the row index of 'comp' must be the constant 0, 1, 2 or 3\n"
          "      P += comp(m, 4, 0);\n"
          "                   ^\n");
    CHECK(Diagnose("displacement t() {\n  matrix m = 1;\n  P += comp(m, 1);\n}\n") ==
          "test.sl:3:8: error: 'comp' expects 3 arguments for a matrix, got 2\n"
          "      P += comp(m, 1);\n"
          "           ^\n");
    CHECK(Diagnose("displacement t(matrix m = P) {\n  P = transform(m, P);\n}\n") ==
          "test.sl:1:23: error: cannot assign a point to matrix parameter 'm'\n"
          "    displacement t(matrix m = P) {\n"
          "                          ^\n");
    CHECK(Diagnose("displacement t() {\n  matrix m = 1;\n  P = u > 0 ? m : P;\n}\n") ==
          "test.sl:3:13: error: the two results of '?:' have incompatible types (matrix and point)\n"
          "      P = u > 0 ? m : P;\n"
          "                ^\n");
    CHECK(Diagnose("displacement t() {\n  matrix m = (1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, \"a\");\n  P = "
                   "transform(m, P);\n}\n") ==
          "test.sl:2:60: error: a matrix's entries must be floats, got a string\n"
          "      matrix m = (1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, \"a\");\n"
          "                                                               ^\n");
    CHECK(Diagnose("displacement t() {\n  P += -(matrix 1);\n}\n") ==
          "test.sl:2:8: error: invalid operand to unary '-' (matrix)\n"
          "      P += -(matrix 1);\n"
          "           ^\n");
}

TEST_CASE("spline, noise and filterstep arguments", "[compiler][diagnostics]") {
    CHECK(Diagnose("displacement t() {\n  P += spline(0.5, 1, 2, 3);\n}\n") ==
          "test.sl:2:8: error: 'spline' expects a float parameter and at least 4 knots\n"
          "      P += spline(0.5, 1, 2, 3);\n"
          "           ^\n");
    CHECK(Diagnose("displacement t() {\n  P += spline(0.5, color(1, 1, 1), P, P, P);\n}\n") ==
          "test.sl:2:36: error: spline knots must all be floats or all triples\n"
          "      P += spline(0.5, color(1, 1, 1), P, P, P);\n"
          "                                       ^\n");
    CHECK(Diagnose("displacement t() {\n  P += spline(\"bezir\", 0.5, 1, 2, 3, 4);\n}\n") ==
          "test.sl:2:15: error: unknown spline basis 'bezir' (catmull-rom, bezier, bspline, hermite, power and linear "
          "are known)\n"
          "      P += spline(\"bezir\", 0.5, 1, 2, 3, 4);\n"
          "                  ^\n");
    CHECK(Diagnose("displacement t() {\n  P += spline(\"bezier\", 0.5, 1, 2, 3, 4, 5);\n}\n") ==
          "test.sl:2:8: error: a bezier spline takes 4 + 3n knots, got 5\n"
          "      P += spline(\"bezier\", 0.5, 1, 2, 3, 4, 5);\n"
          "           ^\n");
    CHECK(Diagnose("displacement t() {\n  P += noise(color(1, 0, 0));\n}\n") ==
          "test.sl:2:8: error: no version of 'noise' takes (color); expected a float, two floats, a point, or a point "
          "and a float\n"
          "      P += noise(color(1, 0, 0));\n"
          "           ^\n");
    CHECK(Diagnose("displacement t() {\n  P += noise(1, 2, 3);\n}\n") ==
          "test.sl:2:8: error: no version of 'noise' takes (float, float, float); expected a float, two floats, a "
          "point, or a point and a float\n"
          "      P += noise(1, 2, 3);\n"
          "           ^\n");
    CHECK(Diagnose("displacement t() {\n  P += pnoise(P);\n}\n") ==
          "test.sl:2:8: error: no version of 'pnoise' takes (point); expected (x, period) with x a float, two floats, "
          "a point, or a point and a float\n"
          "      P += pnoise(P);\n"
          "           ^\n");
    CHECK(Diagnose("displacement t() {\n  P += filterstep(0.5, u, \"blur\", 1);\n}\n") ==
          "test.sl:2:27: error: unknown filterstep parameter 'blur'\n"
          "      P += filterstep(0.5, u, \"blur\", 1);\n"
          "                              ^\n");
    CHECK(Diagnose("displacement t() {\n  P += filterstep(0.5, u, \"width\");\n}\n") ==
          "test.sl:2:27: error: filterstep's optional arguments are pairs of a name and a constant float\n"
          "      P += filterstep(0.5, u, \"width\");\n"
          "                              ^\n");
    CHECK(Diagnose("displacement t() {\n  P += filterstep(0.5, u, \"width\", u);\n}\n") ==
          "test.sl:2:27: error: filterstep's optional arguments are pairs of a name and a constant float\n"
          "      P += filterstep(0.5, u, \"width\", u);\n"
          "                              ^\n");
    CHECK(Diagnose("displacement t() {\n  P += filterstep(0.5);\n}\n") ==
          "test.sl:2:8: error: 'filterstep' expects (float edge, float x) or (float edge, float x0, float x1)\n"
          "      P += filterstep(0.5);\n"
          "           ^\n");
}

TEST_CASE("variables, assignment and casts", "[compiler][diagnostics]") {
    CHECK(Diagnose("displacement t() {\n  x = 1;\n}\n") ==
          "test.sl:2:5: error: assignment to undeclared variable 'x'\n"
          "      x = 1;\n"
          "        ^\n");
    CHECK(Diagnose("displacement t() {\n  dPdu = 1;\n}\n") ==
          "test.sl:2:8: error: cannot assign to 'dPdu': it is a read-only global\n"
          "      dPdu = 1;\n"
          "           ^\n");
    CHECK(Diagnose("displacement t(string mode = \"up\") {\n  mode = \"down\";\n}\n") ==
          "test.sl:2:8: error: cannot assign to 'mode': it is read-only\n"
          "      mode = \"down\";\n"
          "           ^\n");
    CHECK(Diagnose("displacement t() {\n  float x = \"a\";\n}\n") ==
          "test.sl:2:9: error: cannot assign a string to float variable 'x'\n"
          "      float x = \"a\";\n"
          "            ^\n");
    // As prman and aqsis: a warning, the value 0.
    CHECK(Warnings("displacement t() {\n  point q;\n  P += q + N;\n}\n") ==
          "test.sl:3:8: warning: variable 'q' is used before it is assigned a value (it is 0 here)\n"
          "      P += q + N;\n"
          "           ^\n");
    CHECK(Diagnose("displacement t() {\n  float x = float P;\n}\n") ==
          "test.sl:2:13: error: cannot cast a point to float\n"
          "      float x = float P;\n"
          "                ^\n");
    CHECK(Diagnose("displacement t() {\n  P = point \"a\";\n}\n") ==
          "test.sl:2:7: error: cannot cast a string to point\n"
          "      P = point \"a\";\n"
          "          ^\n");
}

TEST_CASE("shader parameters and shader definitions", "[compiler][diagnostics]") {
    CHECK(Diagnose("displacement t(float k = 1; float k = 2) {\n  P += k;\n}\n") ==
          "test.sl:1:35: error: redefinition of parameter 'k'\n"
          "    displacement t(float k = 1; float k = 2) {\n"
          "                                      ^\n");
    CHECK(Diagnose("displacement t(string s = 1) {\n  P += 1;\n}\n") ==
          "test.sl:1:23: error: default value of string parameter 's' must be a string\n"
          "    displacement t(string s = 1) {\n"
          "                          ^\n");
    CHECK(Diagnose("displacement t(float k) {\n  P += k;\n}\n") ==
          "test.sl:1:22: error: parameter 'k' needs a default value\n"
          "    displacement t(float k) {\n"
          "                         ^\n");
    CHECK(Diagnose("displacement a() {\n  P += 1;\n}\ndisplacement b() {\n  P += 2;\n}\n") ==
          "test.sl:4:14: error: only one shader per file is supported\n"
          "    displacement b() {\n"
          "                 ^\n");
}

TEST_CASE("calls nested more than 64 functions deep", "[compiler][diagnostics]") {
    // f0 calls f1 ... calls f70: the 65th nested call (f63 calling f64) is refused.
    std::string source;
    for (int i = 0; i < 70; ++i) source += "void f" + std::to_string(i) + "() { f" + std::to_string(i + 1) + "(); }\n";
    source += "void f70() { }\ndisplacement t() {\n  f0();\n}\n";
    CHECK(Diagnose(source) ==
          "test.sl:64:14: error: calls nest deeper than 64 functions (limit call-depth = 64; raise it with --limit "
          "call-depth=N)\n"
          "    void f63() { f64(); }\n"
          "                 ^\n");
    // 64 levels are fine.
    std::string ok;
    for (int i = 0; i < 63; ++i) ok += "void f" + std::to_string(i) + "() { f" + std::to_string(i + 1) + "(); }\n";
    ok += "void f63() { P += 1; }\ndisplacement t() {\n  f0();\n}\n";
    CHECK(Warnings(ok).empty());
}

TEST_CASE("warnings: unused variables", "[compiler][diagnostics][warnings]") {
    CHECK(Warnings("displacement t() {\n  float unused = 1;\n  P += 1;\n}\n") ==
          "test.sl:2:9: warning: unused variable 'unused'\n"
          "      float unused = 1;\n"
          "            ^\n");
    // In a block, and in a function body.
    CHECK(Warnings("displacement t() {\n  P += 1;\n  if (u > 0.5) {\n      vector w = 1;\n  }\n}\n") ==
          "test.sl:4:14: warning: unused variable 'w'\n"
          "          vector w = 1;\n"
          "                 ^\n");
    CHECK(Warnings("float f(float x) {\n  float y = 2;\n  return x;\n}\ndisplacement t() {\n  P += f(1);\n}\n") ==
          "test.sl:2:9: warning: unused variable 'y'\n"
          "      float y = 2;\n"
          "            ^\n");
    // Parameters (a scene may set them), and variables read in an arm never taken, are not
    // warned about.
    CHECK(Warnings("displacement t(float Km = 1) {\n  P += 1;\n}\n").empty());
    CHECK(Warnings("displacement t() {\n  float k = 2;\n  if (0) P += k;\n  P += 1;\n}\n").empty());
    // After an error, no warnings.
    CHECK(Diagnose("displacement t() {\n  float unused = 1;\n  P += foo;\n}\n") ==
          "test.sl:3:8: error: unknown identifier 'foo'\n"
          "      P += foo;\n"
          "           ^\n");
}

TEST_CASE("warnings: a shader that never changes P or N", "[compiler][diagnostics][warnings]") {
    CHECK(Warnings("displacement t() {\n  float k = u;\n  k += 1;\n}\n") ==
          "test.sl:2:9: warning: unused variable 'k'\n"
          "      float k = u;\n"
          "            ^\n"
          "test.sl:1:14: warning: shader 't' never changes P or N\n"
          "    displacement t() {\n"
          "                 ^\n");
    CHECK(Warnings("displacement t() {\n  P = P;\n}\n") ==
          "test.sl:1:14: warning: shader 't' never changes P or N\n"
          "    displacement t() {\n"
          "                 ^\n");
    // P + 0 * k folds to P.
    CHECK(Warnings("displacement flat(float Km = 1) {\n  float k = Km * u;\n  P = P + 0 * k;\n}\n") ==
          "test.sl:1:14: warning: shader 'flat' never changes P or N\n"
          "    displacement flat(float Km = 1) {\n"
          "                 ^\n");
    CHECK(Warnings("displacement t() {\n  if (0) P += 1;\n}\n") ==
          "test.sl:1:14: warning: shader 't' never changes P or N\n"
          "    displacement t() {\n"
          "                 ^\n");
    // Changing N alone is a change.
    CHECK(Warnings("displacement t() {\n  N = -N;\n}\n").empty());
    // String parameters are folded at their defaults: the warning says so, since a scene may give
    // them a value that moves P.
    CHECK(Warnings("displacement t(string map = \"\"; string space = \"object\"; float Km = 1) {\n"
                   "  if (map != \"\") P += Km * N;\n}\n") ==
          "test.sl:1:14: warning: shader 't' never changes P or N with its string parameters at their defaults "
          "(map = \"\", space = \"object\")\n"
          "    displacement t(string map = \"\"; string space = \"object\"; float Km = 1) {\n"
          "                 ^\n");
}

// ---------------------------------------------------------------------------------------------
// Regression tests: diagnostics bugs found by this suite and fixed

TEST_CASE("an error in a loop body is reported once, not once per unrolled iteration", "[compiler][diagnostics]") {
    // Regression test (a bug found and fixed): LowerLoop lowers the body once per iteration, and each lowering reports again (up to
    // the cap of 50 errors for a varying loop).
    CHECK(Diagnose("displacement t() {\n  float i;\n  for (i = 0; i < 3; i += 1) P += foo;\n}\n") ==
          "test.sl:3:35: error: unknown identifier 'foo'\n"
          "      for (i = 0; i < 3; i += 1) P += foo;\n"
          "                                      ^\n");
    CHECK(Diagnose("displacement t() {\n  float i;\n  for (i = 0; i < 3; i += 1) break 2;\n}\n") ==
          "test.sl:3:30: error: 'break 2' is inside only 1 loop\n"
          "      for (i = 0; i < 3; i += 1) break 2;\n"
          "                                 ^\n");
    CHECK(Diagnose("displacement t() {\n  float i;\n  for (i = 0; i < u; i += 1) P += foo;\n}\n") ==
          "test.sl:3:35: error: unknown identifier 'foo'\n"
          "      for (i = 0; i < u; i += 1) P += foo;\n"
          "                                      ^\n");
    CHECK(
        Warnings(
            "displacement t() {\n  float i;\n  for (i = 0; i < 3; i += 1) {\n    float w = 1;\n  }\n  P += 1;\n}\n") ==
        "test.sl:4:11: warning: unused variable 'w'\n"
        "        float w = 1;\n"
        "              ^\n");
}

TEST_CASE("an error in a function body is reported once, not once per call", "[compiler][diagnostics]") {
    // Regression test (a bug found and fixed): each inlined call lowers the body again and repeats its diagnostics (and the cascade
    // "has no 'return' with a value", see the next test).
    CHECK(Diagnose("float f() {\n  return foo;\n}\ndisplacement t() {\n  P += f() + f();\n}\n") ==
          "test.sl:2:10: error: unknown identifier 'foo'\n"
          "      return foo;\n"
          "             ^\n");
}

TEST_CASE("one mistake gives one message", "[compiler][diagnostics]") {
    // Regression test (a bug found and fixed): a declaration whose initial value has the wrong type leaves the variable without a
    // value, so each use reports "used before it is assigned" too.
    CHECK(Diagnose("displacement t() {\n  float x = \"a\";\n  P += x;\n}\n") ==
          "test.sl:2:9: error: cannot assign a string to float variable 'x'\n"
          "      float x = \"a\";\n"
          "            ^\n");
    // Regression test (a bug found and fixed): a function whose only return has an error also reports "has no 'return' with a value".
    CHECK(Diagnose("float f() {\n  return \"a\";\n}\ndisplacement t() {\n  P += f();\n}\n") ==
          "test.sl:2:10: error: cannot assign a string to the return value\n"
          "      return \"a\";\n"
          "             ^\n");
    CHECK(Diagnose("float f(float x) {\n  return f(x);\n}\ndisplacement t() {\n  P += f(1);\n}\n") ==
          "test.sl:2:10: error: recursive call to 'f': affray inlines functions, so a function cannot call itself\n"
          "      return f(x);\n"
          "             ^\n"
          "test.sl:1:7: note: 'f' is defined here\n"
          "    float f(float x) {\n"
          "          ^\n");
    CHECK(Diagnose("float f() {\n  return;\n}\ndisplacement t() {\n  P += f();\n}\n") ==
          "test.sl:2:3: error: 'return' needs a value in a function returning float\n"
          "      return;\n"
          "      ^\n");
    CHECK(Diagnose("float f() {\n  extern float k;\n  return k;\n}\ndisplacement t() {\n  P += f();\n}\n") ==
          "test.sl:2:16: error: extern variable 'k' is not declared in an enclosing scope\n"
          "      extern float k;\n"
          "                   ^\n");
}

TEST_CASE("a loop body that never runs is still checked", "[compiler][diagnostics]") {
    // Regression test (a bug found and fixed): a loop whose condition is false from the start never lowers its body, so its errors
    // go unreported and the shader compiles (a constant-false if arm is checked).
    CHECK(Diagnose("displacement t() {\n  float i;\n  for (i = 0; i < 0; i += 1) P += foo;\n  P += 1;\n}\n") ==
          "test.sl:3:35: error: unknown identifier 'foo'\n"
          "      for (i = 0; i < 0; i += 1) P += foo;\n"
          "                                      ^\n");
    CHECK(Diagnose("displacement t() {\n  while (0) P += sin(P);\n  P += 1;\n}\n") ==
          "test.sl:2:18: error: no version of 'sin' takes (point); expected (float)\n"
          "      while (0) P += sin(P);\n"
          "                     ^\n");
}

TEST_CASE("a function that is never called is still checked", "[compiler][diagnostics]") {
    // Regression test (a bug found and fixed): functions are checked only when a call inlines them; an uncalled function with an
    // error compiles.
    CHECK(Diagnose("float f() {\n  return foo;\n}\ndisplacement t() {\n  P += 1;\n}\n") ==
          "test.sl:2:10: error: unknown identifier 'foo'\n"
          "      return foo;\n"
          "             ^\n");
}

TEST_CASE("a space name chosen by a varying condition is an error", "[compiler][diagnostics]") {
    // A string chosen at run time compares fine (by its id), but a space must be known when
    // the shader is compiled.
    CHECK(Diagnose("displacement t() {\n  string s = \"world\";\n  if (u > 0.5) s = \"object\";\n  P = transform(s, "
                   "P);\n}\n") ==
          "test.sl:4:17: error: the space name must be known when the shader is compiled (here it depends on a "
          "condition)\n"
          "      P = transform(s, P);\n"
          "                    ^\n");
}

TEST_CASE("an array argument of the wrong size says which sizes", "[compiler][diagnostics]") {
    // Regression test (a bug found and fixed): the message reads "argument 1 of 'sum' is a float array; the parameter 'a' is a float
    // array", which does not say what is wrong (the sizes 2 and 3).
    std::string d = Diagnose(
        "float sum(float a[3]) { return a[0]; }\ndisplacement t() {\n  float b[2] = {1, 2};\n  P += sum(b);\n}\n");
    std::string message = d.substr(0, d.find('\n'));
    message = message.substr(message.find("error: "));
    INFO(message);
    CHECK(message.find('2') != std::string::npos);
    CHECK(message.find('3') != std::string::npos);
}

TEST_CASE("a string parameter of an uncalled function names a space, a basis or a filter parameter",
          "[compiler][diagnostics]") {
    // Regression test (issue 14): checking a function nobody calls gave its string parameters the
    // string with index 0, of a table that could be empty: a segmentation fault, nothing printed.
    // Such a parameter is now unknown while the function is checked; the names are checked at
    // each call instead.
    CHECK(Warnings("float D (string space) { return xcomp(vtransform(space, N)); }\n"
                   "displacement r() { P += 0.1 * N; }\n") == "");
    CHECK(Warnings("point D (string space) { return transform(space, P); }\n"
                   "displacement r() { P += 0.1 * N; }\n") == "");
    CHECK(Warnings("normal D (string a; string b) { return ntransform(a, b, N); }\n"
                   "float S (string basis) { return spline(basis, u, 0, 1, 2, 3); }\n"
                   "float F (string p) { return filterstep(0.5, u, p, 1); }\n"
                   "displacement r() { P += 0.1 * N; }\n") == "");
    // Called, the name is the caller's: a known space works, an unknown one is an error at the
    // call's own use of it, as for a literal.
    CHECK(Warnings("float D (string space) { return zcomp(vtransform(space, N)); }\n"
                   "displacement r() { P += D(\"object\") * 0.1 * N; }\n") == "");
    CHECK(Diagnose("float D (string space) { return zcomp(vtransform(space, N)); }\n"
                   "displacement r() { P += D(\"nowhere\") * 0.1 * N; }\n") ==
          "test.sl:1:50: error: unknown coordinate space 'nowhere'\n"
          "    float D (string space) { return zcomp(vtransform(space, N)); }\n"
          "                                                     ^\n");
}

TEST_CASE("a mistake inside an endless loop is reported before any unrolling", "[compiler][diagnostics][limits]") {
    // Names and types are checked on the loop's body as dead code first: the unknown name is the
    // only error, and the loop is not unrolled at all (no loop-iterations error after it).
    CHECK(Diagnose("displacement t() {\n  float i = 0;\n  while (i < 1) { P += nosuch * N; }\n}\n") ==
          "test.sl:3:24: error: unknown identifier 'nosuch'\n"
          "      while (i < 1) { P += nosuch * N; }\n"
          "                           ^\n");
}

TEST_CASE("the program-ops limit stops unrolling where it is passed", "[compiler][diagnostics][limits]") {
    // 1000 iterations of a body asking for a dozen operations each (the loop's test and step too).
    const std::string source =
        "displacement t() {\n  float i, a = 0;\n  for (i = 0; i < 1000; i += 1)\n    a += sin(u * i);\n"
        "  P += a * N;\n}\n";
    compiler::CompileResult fits = compiler::CompileSource("test.sl", source);
    INFO(fits.diagnostics);
    CHECK(fits.ok());
    CHECK(fits.shader->opsBeforeOptimisation > 10000);
    CHECK(fits.shader->opsBeforeOptimisation < 14000);

    test::ScopedLimit limit(diag::Limit::ProgramOps, 1000);
    // Found where the loop tests its condition again (a statement inside the body that passes it
    // is the place instead, with a note on the loop: limit_program_ops.sl).
    CHECK(Diagnose(source) ==
          "test.sl:3:3: error: the shader grows past 1000 operations as its loops are unrolled and its calls inlined "
          "(limit program-ops = 1000; raise it with --limit program-ops=N)\n"
          "      for (i = 0; i < 1000; i += 1)\n"
          "      ^\n");
}

TEST_CASE("loop-iterations and varying-loop-iterations bound the unrolling", "[compiler][diagnostics][limits]") {
    const std::string constant = "displacement t() {\n  float i;\n  for (i = 0; i < 50; i += 1) P += 0.001 * N;\n}\n";
    CHECK(compiler::CompileSource("test.sl", constant).ok());
    {
        test::ScopedLimit limit(diag::Limit::LoopIterations, 49);
        CHECK(Diagnose(constant).find("this loop runs more than 49 iterations") != std::string::npos);
    }
    // A loop whose count varies over the surface is unrolled varying-loop-iterations times; the
    // paths still running after that are unbounded (NaN), not an error, and not a wrong value.
    const std::string varying = "displacement t() {\n  float x = 0;\n  while (x < u * 10) x += 1;\n  P += x * N;\n}\n";
    // On the unit square (N = +z) the loop counts to ceil(10 u): 3 at u = 0.25, 8 at u = 0.75.
    const compiler::CompiledShader wide = test::CompileOrThrow(varying);
    CHECK(test::PointOnSquare(wide.shade, 0.25, 0.5).z == 3);
    CHECK(test::PointOnSquare(wide.shade, 0.75, 0.5).z == 8);
    test::ScopedLimit limit(diag::Limit::VaryingLoopIterations, 5);
    const compiler::CompiledShader narrow = test::CompileOrThrow(varying);
    CHECK(test::PointOnSquare(narrow.shade, 0.25, 0.5).z == 3);
    CHECK(std::isnan(test::PointOnSquare(narrow.shade, 0.75, 0.5).z));
}
