// tests/lang/parse_test.cpp: the lexer and parser (lang/lexer.l, lang/parser.y, lang/parse.cpp)
// and the printed tree (lang/ast.cpp). Valid programs are checked through ToString; invalid ones
// through the exact text of Diagnostics::format(), so a change in any message shows up here.
#include <catch2/catch.hpp>

#include <iterator>
#include <optional>
#include <random>
#include <string>

#include "lang/parse.h"
#include "tests/test_util.h"

namespace affray::lang {
namespace {

struct Parsed {
    TranslationUnit unit;
    std::string errors;  // Diagnostics::format()
    int errorCount = 0;
};

Parsed Run(const std::string& text) {
    SourceFile file("test.sl", text);
    Diagnostics diags(file);
    Parsed out;
    out.unit = Parse(diags);
    out.errors = diags.format();
    out.errorCount = diags.errorCount();
    return out;
}

// The formatted diagnostics for `text`, which must not parse cleanly.
std::string Errors(const std::string& text) {
    Parsed p = Run(text);
    CHECK(p.errorCount > 0);
    return p.errors;
}

// The printed shaders of `text`, which must parse without a diagnostic.
std::string Tree(const std::string& text) {
    Parsed p = Run(text);
    INFO(p.errors);
    REQUIRE(p.errors.empty());
    std::string out;
    for (const ShaderDef& s : p.unit.shaders) {
        if (!out.empty()) out += '\n';
        out += ToString(s);
    }
    return out;
}

// The printed functions of `text`, then its shaders, one a line; `text` must parse cleanly.
std::string Unit(const std::string& text) {
    Parsed p = Run(text);
    INFO(p.errors);
    REQUIRE(p.errors.empty());
    std::string out;
    for (const std::shared_ptr<FunctionDef>& f : p.unit.functions) out += ToString(*f) + "\n";
    for (const ShaderDef& s : p.unit.shaders) out += ToString(s) + "\n";
    return out;
}

// The printed statements of a displacement shader with this body.
std::string Body(const std::string& body) {
    Parsed p = Run("displacement d() {\n" + body + "\n}\n");
    INFO(p.errors);
    REQUIRE(p.errors.empty());
    REQUIRE(p.unit.shaders.size() == 1);
    std::string out;
    for (const StmtPtr& s : p.unit.shaders[0].body) {
        if (!out.empty()) out += ' ';
        out += ToString(*s);
    }
    return out;
}

// The printed value of `x = <expr>;`.
std::string Value(const std::string& expr) {
    Parsed p = Run("displacement d() { x = " + expr + "; }");
    INFO(p.errors);
    REQUIRE(p.errors.empty());
    const Stmt& s = *p.unit.shaders.at(0).body.at(0);
    REQUIRE(s.kind == StmtKind::Expr);
    REQUIRE(s.expr->kind == ExprKind::Assign);
    return ToString(*s.expr->args.at(0));
}

}  // namespace

// --- Valid programs ----------------------------------------------------------------------------

TEST_CASE("binary operators follow RSL precedence", "[lang]") {
    CHECK(Value("a + b . c") == "(+ a (. b c))");
    CHECK(Value("a ^ b * c") == "(^ a (* b c))");
    CHECK(Value("a * b . c") == "(* a (. b c))");
    CHECK(Value("a + b ^ c") == "(+ a (^ b c))");
    CHECK(Value("a - b - c") == "(- (- a b) c)");
    CHECK(Value("a / b * c") == "(* (/ a b) c)");
    CHECK(Value("a . b . c") == "(. (. a b) c)");
    CHECK(Value("a < b + c == d") == "(== (< a (+ b c)) d)");
    CHECK(Value("a || b && c <= d") == "(|| a (&& b (<= c d)))");
    CHECK(Value("a != b || c >= d && e > f") == "(|| (!= a b) (&& (>= c d) (> e f)))");
}

TEST_CASE("unary operators bind tighter than dot", "[lang]") {
    CHECK(Value("-a . b") == "(. (- a) b)");
    CHECK(Value("!a && b") == "(&& (! a) b)");
    CHECK(Value("+a") == "a");
    CHECK(Value("- -a") == "(- (- a))");
    CHECK(Value("-1") == "(- 1)");
}

TEST_CASE("assignment and ?: are right associative", "[lang]") {
    CHECK(Body("a = b = c;") == "(= a (= b c))");
    CHECK(Value("c ? x : y ? z : w") == "(? c x (? y z w))");
    CHECK(Value("c ? x = 1 : y") == "(? c (= x 1) y)");
    CHECK(Value("a || b ? c + d : e") == "(? (|| a b) (+ c d) e)");
}

TEST_CASE("compound assignment", "[lang]") {
    CHECK(Body("P += Km * N;") == "(+= P (* Km N))");
    CHECK(Body("a -= 1; b *= 2; c /= 3;") == "(-= a 1) (*= b 2) (/= c 3)");
    CHECK(Body("(a) = 1;") == "(= a 1)");
}

TEST_CASE("casts take a unary operand and an optional space", "[lang]") {
    CHECK(Value("point \"shader\" (1,2,3)") == "(cast point \"shader\" (triple 1 2 3))");
    CHECK(Value("point \"shader\"(1, 2, 3)") == "(cast point \"shader\" (triple 1 2 3))");
    CHECK(Value("float noise(P)") == "(cast float (call noise P))");
    CHECK(Value("float noise(P) * 2") == "(* (cast float (call noise P)) 2)");
    CHECK(Value("point(0.5, 0.5, 0)") == "(cast point (triple 0.5 0.5 0))");
    CHECK(Value("vector \"world\" -N") == "(cast vector \"world\" (- N))");
    CHECK(Value("color \"rgb\" (r, g, b)") == "(cast color \"rgb\" (triple r g b))");
    CHECK(Value("normal N . I") == "(. (cast normal N) I)");
    CHECK(Value("-float x") == "(- (cast float x))");
    CHECK(Value("float \"a\" + 1") == "(cast float \"a\" 1)");
}

TEST_CASE("a parenthesised triple is not a parenthesised expression", "[lang]") {
    CHECK(Value("(a)") == "a");
    CHECK(Value("((a + b)) * c") == "(* (+ a b) c)");
    CHECK(Value("(a, b + 1, c)") == "(triple a (+ b 1) c)");
    CHECK(Value("(1, (2), (3, 4, 5))") == "(triple 1 2 (triple 3 4 5))");
}

TEST_CASE("calls, numbers, strings and the dot operator", "[lang]") {
    CHECK(Value("f()") == "(call f)");
    CHECK(Value("mix(a, b, smoothstep(0, 1, t))") == "(call mix a b (call smoothstep 0 1 t))");
    CHECK(Value("1 + 1. + .5 + 1.5e-3 + 2E+4 + 1e-999") == "(+ (+ (+ (+ (+ 1 1) 0.5) 0.0015) 20000) 0)");
    CHECK(Value("N.I + N . I + (N).(I)") == "(+ (+ (. N I) (. N I)) (. N I))");
    CHECK(Value("\"a\\\"b\\n\\t\\\\\"") == "\"a\\\"b\\n\\t\\\\\"");
}

TEST_CASE("surface() and displacement() are calls in an expression, shader kinds at the top", "[lang]") {
    CHECK(Value("surface(\"Kd\", k) + displacement(\"Km\", k)") ==
          "(+ (call surface \"Kd\" k) (call displacement \"Km\" k))");
    const std::string unit = Unit(
        "float f() { surface(\"Kd\", k); return displacement(\"Km\", k); }\n"
        "surface s() { }\ndisplacement d() { }\n");
    CHECK(unit.find("(call surface") != std::string::npos);
    CHECK(unit.find("(call displacement") != std::string::npos);
    CHECK(Run("surface s() { } displacement d() { }").unit.shaders.size() == 2);
}

TEST_CASE("shader parameters share a type across commas", "[lang]") {
    CHECK(Tree("displacement d(float a = 1, b = 2; point c = 0;) {}") ==
          "(displacement d (params (float a 1) (float b 2) (point c 0)) (body))");
    CHECK(Tree("displacement d(float a = 1; string s = \"x\") {}") ==
          "(displacement d (params (float a 1) (string s \"x\")) (body))");
    CHECK(Tree("displacement d(output varying vector v = 0, w; uniform color c = 1) {}") ==
          "(displacement d (params (output varying vector v 0) (output varying vector w) "
          "(uniform color c 1)) (body))");
    CHECK(Tree("surface s() {} light l() {} volume v() {} imager i() {}") ==
          "(surface s (params) (body))\n(light l (params) (body))\n(volume v (params) (body))\n"
          "(imager i (params) (body))");
}

TEST_CASE("a shader class is the displacement shader its displacement method runs", "[lang]") {
    // Members first, then the methods a run reaches (the entries renamed class::...), then the
    // calls of construct/begin and displacement. surface() and what only it calls are left out,
    // unchecked; so is a method nobody calls.
    CHECK(Tree("class c(float Km = 1) {\n"
               "  varying float m = 0;\n"
               "  public void surface(output color Ci, Oi) { illuminance(P) { Ci += shade(); } }\n"
               "  color shade() { return diffuse(N); }\n"
               "  float h(float x) { return x * m; }\n"
               "  float unused() { return 1; }\n"
               "  public void begin() { m = Km; }\n"
               "  public void displacement(output point P; output normal N) { P += h(2) * N; }\n"
               "}\n") ==
          "(displacement c (params (float Km 1)) (body (decl (varying float m 0)) "
          "(function float h (params (float x)) (body (return (* x m)))) "
          "(function void class::begin (params) (body (= m Km))) "
          "(function void class::displacement (params) (body (+= P (* (call h 2) N)))) "
          "(call class::begin) (call class::displacement)))");
    // construct() runs before begin(); a displacement method may take no parameters.
    CHECK(Tree("class c() { void begin() {} void construct() {} void displacement() { P += 1; } }") ==
          "(displacement c (params) (body (function void class::begin (params) (body)) "
          "(function void class::construct (params) (body)) "
          "(function void class::displacement (params) (body (+= P 1))) "
          "(call class::construct) (call class::begin) (call class::displacement)))");
    auto starts = [](const std::string& text, const std::string& prefix) { return text.rfind(prefix, 0) == 0; };
    CHECK(starts(Errors("class c(float a = 1) { public void surface(output color Ci, Oi) { Ci = 1; } }"),
                 "test.sl:1:7: error: class 'c' has no displacement method: affray runs a shader class by its "
                 "`public void displacement(output point P; output normal N)`\n"));
    CHECK(starts(Errors("class c() { void displacement(output point Q) { } }"),
                 "test.sl:1:44: error: parameter 'Q' of a displacement method: its parameters are the globals it "
                 "changes, `output point P; output normal N`\n"));
    CHECK(starts(Errors("class c() { void begin(float x) { } void displacement() { } }"),
                 "test.sl:1:30: error: method 'begin' of a shader class takes no parameters\n"));
    CHECK(starts(Errors("class c() { void displacement() { } float displacement() { return 1; } }"),
                 "test.sl:1:43: error: redefinition of method 'displacement' of class 'c'\n"));
}

TEST_CASE("statements", "[lang]") {
    CHECK(Body("if (a < b) x = 1; else { x = 2; y = 3; }") == "(if (< a b) (= x 1) (block (= x 2) (= y 3)))");
    CHECK(Body("if (a) if (b) x = 1; else x = 2;") == "(if a (if b (= x 1) (= x 2)))");
    CHECK(Body("for (i = 0; i < 10; i += 1) { P += N; }") == "(for (= i 0) (< i 10) (+= i 1) (block (+= P N)))");
    CHECK(Body("for (;;) break;") == "(for () () () (break))");
    CHECK(Body("while (i > 0) { i -= 1; continue 2; break 1; }") ==
          "(while (> i 0) (block (-= i 1) (continue 2) (break)))");
    CHECK(Body("float a = 1, b; uniform point p; varying normal n = N;") ==
          "(decl (float a 1) (float b)) (decl (uniform point p)) (decl (varying normal n N))");
    CHECK(Body("; {} return; return x + 1; f(x);") == "(empty) (block) (return) (return (+ x 1)) (call f x)");
}

TEST_CASE("the wave shader", "[lang]") {
    const char* source = R"(
displacement wave(float Km = 0.1, freq = 20, decay = 3; point center = point(0.5, 0.5, 0);)
{
    float r = distance(P, center);
    P += Km * exp(-decay * r) * sin(freq * 2 * PI * r) * normalize(N);
    N = calculatenormal(P);
}
)";
    CHECK(Tree(source) ==
          "(displacement wave (params (float Km 0.1) (float freq 20) (float decay 3) "
          "(point center (cast point (triple 0.5 0.5 0)))) (body "
          "(decl (float r (call distance P center))) "
          "(+= P (* (* (* Km (call exp (* (- decay) r))) (call sin (* (* (* freq 2) PI) r))) "
          "(call normalize N))) "
          "(= N (call calculatenormal P))))");
}

TEST_CASE("the matrix type", "[lang]") {
    CHECK(Tree("displacement d(matrix m = 1; uniform matrix w = matrix \"world\" 1) {}") ==
          "(displacement d (params (matrix m 1) (uniform matrix w (cast matrix \"world\" 1))) "
          "(body))");
    CHECK(Body("matrix q = m, r; varying matrix v;") == "(decl (matrix q m) (matrix r)) (decl (varying matrix v))");
    CHECK(Value("matrix \"shader\" 1") == "(cast matrix \"shader\" 1)");
    CHECK(Value("matrix(m)") == "(cast matrix m)");
    CHECK(Unit("matrix f(matrix a) { return a; }\ndisplacement d() {}") ==
          "(function matrix f (params (matrix a)) (body (return a)))\n"
          "(displacement d (params) (body))\n");
}

TEST_CASE("16-tuples are matrices", "[lang]") {
    CHECK(Value("(1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1)") == "(tuple16 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1)");
    CHECK(Value("matrix \"world\" (a, b, c, d, e, f, g, h, i, j, k, l, m, n, o, (p + 1))") ==
          "(cast matrix \"world\" (tuple16 a b c d e f g h i j k l m n o (+ p 1)))");
    CHECK(Value("(1, 2, (3, 4, 5))") == "(triple 1 2 (triple 3 4 5))");
}

TEST_CASE("array declarations and initialiser lists", "[lang]") {
    CHECK(Body("float a[3]; float b[3] = {1, 2, 3}, c, e[1] = {x + 1};") ==
          "(decl (float a[3])) (decl (float b[3] {1 2 3}) (float c) (float e[1] {(+ x 1)}))");
    CHECK(Body("point pts[2] = {(0,0,0), (1,1,1)}; uniform color k[2] = {0, color(1,0,0)};") ==
          "(decl (point pts[2] {(triple 0 0 0) (triple 1 1 1)})) "
          "(decl (uniform color k[2] {0 (cast color (triple 1 0 0))}))");
    CHECK(Tree("displacement d(float a[3] = {1, 2, 3}, s = 1; output varying point p[2] = "
               "{P, N};) {}") ==
          "(displacement d (params (float a[3] {1 2 3}) (float s 1) "
          "(output varying point p[2] {P N})) (body))");
    // A parsed declaration holds what the compiler needs.
    Parsed p = Run("displacement d() { float a[2] = {1, 2}, b = 3, c[4]; }");
    REQUIRE(p.errors.empty());
    const std::vector<VarDecl>& decls = p.unit.shaders.at(0).body.at(0)->decls;
    REQUIRE(decls.size() == 3);
    CHECK(decls[0].arraySize == 2);
    CHECK(decls[0].hasInitList);
    CHECK(decls[0].init == nullptr);
    CHECK(decls[0].initList.size() == 2);
    CHECK(decls[1].arraySize == -1);
    CHECK(!decls[1].hasInitList);
    CHECK(decls[1].init != nullptr);
    CHECK(decls[2].arraySize == 4);
    CHECK(!decls[2].hasInitList);
    CHECK(decls[2].init == nullptr);
}

TEST_CASE("array elements in expressions and as assignment targets", "[lang]") {
    CHECK(Value("a[i]") == "([] a i)");
    CHECK(Value("a[i + 1] * b[a[0]]") == "(* ([] a (+ i 1)) ([] b ([] a 0)))");
    CHECK(Value("-a[1] . v[2]") == "(. (- ([] a 1)) ([] v 2))");
    CHECK(Value("float a[1]") == "(cast float ([] a 1))");
    CHECK(Value("(a)[1]") == "([] a 1)");
    CHECK(Body("a[i] = x; a[0] += 1; a[1] -= 2; a[2] *= 3; a[3] /= 4;") ==
          "(= ([] a i) x) (+= ([] a 0) 1) (-= ([] a 1) 2) (*= ([] a 2) 3) (/= ([] a 3) 4)");
    CHECK(Body("a[i] = b[j] = c;") == "(= ([] a i) (= ([] b j) c))");
    CHECK(Body("for (i = 0; i < 3; i += 1) s += a[i];") == "(for (= i 0) (< i 3) (+= i 1) (+= s ([] a i)))");
    // The element's assignment keeps the array's name, the value and then the index.
    Parsed p = Run("displacement d() {\n  a[i + 1] += v;\n}");
    REQUIRE(p.errors.empty());
    const Expr& assign = *p.unit.shaders.at(0).body.at(0)->expr;
    CHECK(assign.kind == ExprKind::Assign);
    CHECK(assign.name == "a");
    REQUIRE(assign.args.size() == 2);
    CHECK(ToString(*assign.args[0]) == "v");
    CHECK(ToString(*assign.args[1]) == "(+ i 1)");
}

TEST_CASE("user functions at the top level", "[lang]") {
    CHECK(Unit("float f(float x; output point p) { p = P; return x; }\n"
               "displacement d() { P += f(1, Q) * N; }\n"
               "void g(float a, b; uniform vector v; output varying float r[]; point q[2];) {\n"
               "    r[0] = a + b;\n"
               "    return;\n"
               "}\n"
               "color c() { return 1; }\n") ==
          "(function float f (params (float x) (output point p)) "
          "(body (= p P) (return x)))\n"
          "(function void g (params (float a) (float b) (uniform vector v) "
          "(output varying float r[]) (point q[2])) (body (= ([] r 0) (+ a b)) (return)))\n"
          "(function color c (params) (body (return 1)))\n"
          "(displacement d (params) (body (+= P (* (call f 1 Q) N))))\n");
    Parsed p = Run("displacement d() {}\n\nstring  name(float x) { return \"a\"; }");
    REQUIRE(p.errors.empty());
    REQUIRE(p.unit.functions.size() == 1);
    const FunctionDef& f = *p.unit.functions[0];
    CHECK(f.returnType == TypeName::String);
    CHECK(f.name == "name");
    CHECK(f.loc.line == 3);
    CHECK(f.loc.column == 9);
    CHECK(f.params.at(0).loc.column == 20);
}

TEST_CASE("functions nested in shader and function bodies", "[lang]") {
    CHECK(Body("float h(float z) {\n"
               "    extern point P;\n"
               "    float k(float w) { extern float z; return w * z; }\n"
               "    return k(z);\n"
               "}\n"
               "P += h(1) * N;") ==
          "(function float h (params (float z)) (body (decl (extern point P)) "
          "(function float k (params (float w)) (body (decl (extern float z)) (return (* w z)))) "
          "(return (call k z)))) (+= P (* (call h 1) N))");
    Parsed p = Run("displacement d() {\n  void v() {}\n}");
    REQUIRE(p.errors.empty());
    const Stmt& s = *p.unit.shaders.at(0).body.at(0);
    CHECK(s.kind == StmtKind::FunctionDef);
    REQUIRE(s.function != nullptr);
    CHECK(s.function->returnType == TypeName::Void);
    CHECK(s.function->loc.column == 8);
    CHECK(p.unit.functions.empty());
}

TEST_CASE("extern declarations", "[lang]") {
    CHECK(Body("extern point P; extern varying float x, y[]; extern uniform normal n[3];") ==
          "(decl (extern point P)) (decl (extern varying float x) (extern varying float y[])) "
          "(decl (extern uniform normal n[3]))");
    Parsed p = Run("float f() { extern float Km; return Km; } displacement d() {}");
    REQUIRE(p.errors.empty());
    const VarDecl& v = p.unit.functions.at(0)->body.at(0)->decls.at(0);
    CHECK(v.isExtern);
    CHECK(v.init == nullptr);
    CHECK(!v.hasInitList);
}

TEST_CASE("return with and without a value, and older forms inside functions", "[lang]") {
    CHECK(Unit("float f(float a, b;) {\n"
               "    if (a > b) return; else return a - b;\n"
               "    while (1) { for (;;) { break 2; continue 2; } }\n"
               "    return point \"world\" (a, b, 0) . vector \"shader\"(0, 0, 1);\n"
               "}\n"
               "displacement d() { return; }\n") ==
          "(function float f (params (float a) (float b)) (body "
          "(if (> a b) (return) (return (- a b))) "
          "(while 1 (block (for () () () (block (break 2) (continue 2))))) "
          "(return (. (cast point \"world\" (triple a b 0)) (cast vector \"shader\" "
          "(triple 0 0 1))))))\n"
          "(displacement d (params) (body (return)))\n");
}

TEST_CASE("nodes carry the location of their key token", "[lang]") {
    Parsed p =
        Run("displacement\n"
            "  wave(float Km = 1)\n"
            "{\n"
            "  P += -a . b;\n"
            "  if (x) y = c ? (1,2,3) : point f(1);\n"
            "}\n");
    REQUIRE(p.errors.empty());
    const ShaderDef& s = p.unit.shaders.at(0);
    CHECK(s.loc.line == 2);
    CHECK(s.loc.column == 3);
    CHECK(s.params.at(0).loc.column == 14);
    const Stmt& assign = *s.body.at(0);
    CHECK(assign.loc.column == 3);        // the first token
    CHECK(assign.expr->loc.column == 5);  // +=
    const Expr& dot = *assign.expr->args.at(0);
    CHECK(dot.loc.column == 11);                         // .
    CHECK(dot.args.at(0)->loc.column == 8);              // unary -
    CHECK(dot.args.at(0)->args.at(0)->loc.column == 9);  // a
    const Stmt& ifs = *s.body.at(1);
    CHECK(ifs.loc.line == 5);
    CHECK(ifs.loc.column == 3);
    const Expr& ternary = *ifs.body.at(0)->expr->args.at(0);
    CHECK(ternary.loc.column == 16);                          // ?
    CHECK(ternary.args.at(1)->loc.column == 18);              // (
    CHECK(ternary.args.at(2)->loc.column == 28);              // point
    CHECK(ternary.args.at(2)->args.at(0)->loc.column == 34);  // f

    Parsed q = Run("displacement d() {\n  x = a [i];\n  b[j] = 1;\n}\n");
    REQUIRE(q.errors.empty());
    const Expr& index = *q.unit.shaders.at(0).body.at(0)->expr->args.at(0);
    CHECK(index.kind == ExprKind::Index);
    CHECK(index.loc.column == 9);              // [
    CHECK(index.args.at(0)->loc.column == 7);  // a
    const Expr& element = *q.unit.shaders.at(0).body.at(1)->expr;
    CHECK(element.loc.column == 8);              // =
    CHECK(element.args.at(1)->loc.column == 5);  // j
}

TEST_CASE("pragmas are ignored and line markers renumber", "[lang]") {
    Parsed p =
        Run("#pragma once\n  # 40 \"wave.sl\"\ndisplacement d() {}\n#line 7\n"
            "surface s() {}\n");
    REQUIRE(p.errors.empty());
    CHECK(p.unit.shaders.at(0).loc.line == 40);
    CHECK(p.unit.shaders.at(1).loc.line == 7);
}

// --- Invalid programs --------------------------------------------------------------------------

TEST_CASE("missing semicolon", "[lang]") {
    CHECK(Errors("displacement d()\n{\n    float r = 1\n    P += r;\n}\n") ==
          "test.sl:4:5: error: syntax error, unexpected identifier, expecting ';'\n"
          "        P += r;\n"
          "        ^\n");
}

TEST_CASE("missing closing parenthesis", "[lang]") {
    CHECK(Errors("displacement d()\n{\n    P = sin(r;\n}\n") ==
          "test.sl:3:14: error: syntax error, unexpected ';', expecting ')'\n"
          "        P = sin(r;\n"
          "                 ^\n");
    CHECK(Errors("displacement d()\n{\n    if (r > 1 {\n        P = 0;\n    }\n}\n") ==
          "test.sl:3:15: error: syntax error, unexpected '{', expecting ')'\n"
          "        if (r > 1 {\n"
          "                  ^\n");
}

TEST_CASE("unbalanced braces", "[lang]") {
    CHECK(Errors("displacement d()\n{\n    P = 1;\n") ==
          "test.sl:3:11: error: syntax error, unexpected end of file\n"
          "        P = 1;\n"
          "              ^\n");
    CHECK(Errors("displacement d()\n{\n    P = 1;\n}\n}\n") ==
          "test.sl:5:1: error: syntax error, unexpected '}'\n"
          "    }\n"
          "    ^\n");
}

TEST_CASE("unexpected token at top level", "[lang]") {
    CHECK(Errors("Km = 1;\n") ==
          "test.sl:1:1: error: syntax error, unexpected identifier\n"
          "    Km = 1;\n"
          "    ^\n");
    // A type at the top level starts a function definition: there are no global variables.
    CHECK(Errors("float Km = 1;\n") ==
          "test.sl:1:10: error: syntax error, unexpected '=', expecting '('\n"
          "    float Km = 1;\n"
          "             ^\n");
}

TEST_CASE("invalid characters", "[lang]") {
    // The lexer's message stands alone: no syntax error follows for the same token.
    CHECK(Errors("displacement d()\n{\n    P = P $ N;\n}\n") ==
          "test.sl:3:11: error: invalid character '$'\n"
          "        P = P $ N;\n"
          "              ^\n");
    CHECK(Errors("displacement d()\n{\n\tP = P + " + std::string(1, '\0') + ";\n}\n") ==
          "test.sl:3:10: error: invalid character '\\x00'\n"
          "    \tP = P + \\x00;\n"
          "    \t        ^\n");
    CHECK(Errors("displacement d() { x = \xCF\x80; }") ==
          "test.sl:1:24: error: invalid character '\xCF\x80'\n"
          "    displacement d() { x = \xCF\x80; }\n"
          "                           ^\n");
}

TEST_CASE("unterminated comment", "[lang]") {
    CHECK(Errors("displacement d()\n{\n    /* scale\n    P *= 2;\n}\n") ==
          "test.sl:3:5: error: unterminated comment\n"
          "        /* scale\n"
          "        ^\n");
}

TEST_CASE("unterminated string", "[lang]") {
    CHECK(Errors("displacement d() {\n    s = \"bumps;\n}\n") ==
          "test.sl:2:9: error: unterminated string\n"
          "        s = \"bumps;\n"
          "            ^\n"
          "test.sl:3:1: error: syntax error, unexpected '}', expecting ';'\n"
          "    }\n"
          "    ^\n");
}

TEST_CASE("malformed numbers and escapes", "[lang]") {
    CHECK(Errors("displacement d()\n{\n    P = 1e + 1.2.3;\n}\n") ==
          "test.sl:3:9: error: malformed number '1e'\n"
          "        P = 1e + 1.2.3;\n"
          "            ^\n"
          "test.sl:3:14: error: malformed number '1.2.3'\n"
          "        P = 1e + 1.2.3;\n"
          "                 ^\n");
    CHECK(Errors("displacement d() { x = 1e999; s = \"a\\qb\"; }") ==
          "test.sl:1:24: error: number '1e999' is too large\n"
          "    displacement d() { x = 1e999; s = \"a\\qb\"; }\n"
          "                           ^\n"
          "test.sl:1:37: error: unknown escape sequence '\\q' in string\n"
          "    displacement d() { x = 1e999; s = \"a\\qb\"; }\n"
          "                                        ^\n");
}

TEST_CASE("tuples other than triples and 16-tuples", "[lang]") {
    CHECK(Errors("displacement d()\n{\n    P = (1, 2);\n}\n") ==
          "test.sl:3:9: error: a tuple must have 3 or 16 components\n"
          "        P = (1, 2);\n"
          "            ^\n");
    CHECK(Errors("displacement d() {\n    m = (1,2,3,4,5,6,7,8,9,10,11,12,13,14,15);\n}\n") ==
          "test.sl:2:9: error: a tuple must have 3 or 16 components\n"
          "        m = (1,2,3,4,5,6,7,8,9,10,11,12,13,14,15);\n"
          "            ^\n");
}

TEST_CASE("assignment to something other than a variable", "[lang]") {
    CHECK(Errors("displacement d()\n{\n    1 = x;\n    a + b += c;\n}\n") ==
          "test.sl:3:7: error: left side of assignment must be a variable or an array element\n"
          "        1 = x;\n"
          "          ^\n"
          "test.sl:4:11: error: left side of assignment must be a variable or an array element\n"
          "        a + b += c;\n"
          "              ^\n");
    // Only an element of a named array: not of a call's result, nor of an element.
    CHECK(Errors("displacement d()\n{\n    f(x)[1] = 2;\n    a[1][2] *= 3;\n}\n") ==
          "test.sl:3:13: error: left side of assignment must be a variable or an array element\n"
          "        f(x)[1] = 2;\n"
          "                ^\n"
          "test.sl:4:13: error: left side of assignment must be a variable or an array element\n"
          "        a[1][2] *= 3;\n"
          "                ^\n");
}

TEST_CASE("a missing closing bracket", "[lang]") {
    CHECK(Errors("displacement d()\n{\n    P += a[1;\n    float b[2;\n    N = 0;\n}\n") ==
          "test.sl:3:13: error: syntax error, unexpected ';', expecting ']'\n"
          "        P += a[1;\n"
          "                ^\n"
          "test.sl:4:14: error: syntax error, unexpected ';', expecting ']'\n"
          "        float b[2;\n"
          "                 ^\n");
}

TEST_CASE("array initialisers without braces or of the wrong length", "[lang]") {
    CHECK(Errors("displacement d()\n{\n    float a[3] = (1, 2, 3);\n}\n") ==
          "test.sl:3:18: error: the initial values of array 'a' must be a list in braces, as in "
          "{1, 2, 3}\n"
          "        float a[3] = (1, 2, 3);\n"
          "                     ^\n");
    // Without braces the list's commas then look like more names.
    CHECK(Errors("displacement d()\n{\n    float a[3] = 1, 2, 3;\n}\n") ==
          "test.sl:3:18: error: the initial values of array 'a' must be a list in braces, as in "
          "{1, 2, 3}\n"
          "        float a[3] = 1, 2, 3;\n"
          "                     ^\n"
          "test.sl:3:21: error: syntax error, unexpected number, expecting identifier\n"
          "        float a[3] = 1, 2, 3;\n"
          "                        ^\n");
    CHECK(Errors("displacement d(float a[3] = {1, 2})\n"
                 "{\n    float b = {1}, c[1] = {1, 2};\n}\n") ==
          "test.sl:1:29: error: array 'a' of size 3 has 2 initial values\n"
          "    displacement d(float a[3] = {1, 2})\n"
          "                                ^\n"
          "test.sl:3:15: error: 'b' is not an array; only an array takes a list in braces\n"
          "        float b = {1}, c[1] = {1, 2};\n"
          "                  ^\n"
          "test.sl:3:27: error: array 'c' of size 1 has 2 initial values\n"
          "        float b = {1}, c[1] = {1, 2};\n"
          "                              ^\n");
}

TEST_CASE("array sizes", "[lang]") {
    CHECK(Errors("displacement d(float p[])\n{\n    float a[];\n    float b[0], c[2.5];\n"
                 "    float e[n];\n}\n") ==
          "test.sl:1:22: error: array 'p' needs a size (only function parameters and externs may "
          "omit it)\n"
          "    displacement d(float p[])\n"
          "                         ^\n"
          "test.sl:3:11: error: array 'a' needs a size (only function parameters and externs may "
          "omit it)\n"
          "        float a[];\n"
          "              ^\n"
          "test.sl:4:13: error: the array size must be a positive integer\n"
          "        float b[0], c[2.5];\n"
          "                ^\n"
          "test.sl:4:19: error: the array size must be a positive integer\n"
          "        float b[0], c[2.5];\n"
          "                      ^\n"
          "test.sl:5:13: error: syntax error, unexpected identifier, expecting number or ']'\n"
          "        float e[n];\n"
          "                ^\n");
}

TEST_CASE("a bad initialiser list is skipped up to its '}'", "[lang]") {
    CHECK(Errors("displacement d()\n{\n    float a[2] = {1, 2 3}, b = 1;\n    float c[1] = {};\n"
                 "    P = 1 +;\n}\n") ==
          "test.sl:3:24: error: syntax error, unexpected number, expecting ',' or '}'\n"
          "        float a[2] = {1, 2 3}, b = 1;\n"
          "                           ^\n"
          "test.sl:4:19: error: syntax error, unexpected '}'\n"
          "        float c[1] = {};\n"
          "                      ^\n"
          "test.sl:5:12: error: syntax error, unexpected ';'\n"
          "        P = 1 +;\n"
          "               ^\n");
    Parsed p = Run("displacement d() { float a[2] = {1 2}, b = 1; c = 2; }");
    REQUIRE(p.unit.shaders.size() == 1);
    CHECK(ToString(p.unit.shaders[0]) == "(displacement d (params) (body (decl (float a[2] {}) (float b 1)) (= c 2)))");
}

TEST_CASE("function definitions without a body", "[lang]") {
    CHECK(Errors("float f(float x);\ndisplacement d()\n{\n    void g();\n    P = 1 +;\n}\n") ==
          "test.sl:1:17: error: syntax error, unexpected ';', expecting '{'\n"
          "    float f(float x);\n"
          "                    ^\n"
          "test.sl:4:13: error: syntax error, unexpected ';', expecting '{'\n"
          "        void g();\n"
          "                ^\n"
          "test.sl:5:12: error: syntax error, unexpected ';'\n"
          "        P = 1 +;\n"
          "               ^\n");
    CHECK(Errors("displacement d() {}\nfloat f(float x)\n") ==
          "test.sl:2:17: error: syntax error, unexpected end of file, expecting '{'\n"
          "    float f(float x)\n"
          "                    ^\n");
}

TEST_CASE("bad function parameters", "[lang]") {
    CHECK(Errors("float f(float x = 1; point p[2] = {0, 1}; float q) { return x; }\n"
                 "displacement d() {}\n") ==
          "test.sl:1:15: error: parameter 'x' of function 'f' cannot have a default value\n"
          "    float f(float x = 1; point p[2] = {0, 1}; float q) { return x; }\n"
          "                  ^\n"
          "test.sl:1:28: error: parameter 'p' of function 'f' cannot have a default value\n"
          "    float f(float x = 1; point p[2] = {0, 1}; float q) { return x; }\n"
          "                               ^\n");
    // The body of a function whose parameters do not parse is still read.
    Parsed p = Run("float f(float x; {\n    return x;\n}\ndisplacement d() { P = ; }\n");
    CHECK(p.errors ==
          "test.sl:1:18: error: syntax error, unexpected '{'\n"
          "    float f(float x; {\n"
          "                     ^\n"
          "test.sl:4:24: error: syntax error, unexpected ';'\n"
          "    displacement d() { P = ; }\n"
          "                           ^\n");
    REQUIRE(p.unit.functions.size() == 1);
    CHECK(ToString(*p.unit.functions[0]) == "(function float f (params) (body (return x)))");
}

TEST_CASE("extern with an initial value", "[lang]") {
    CHECK(Errors("displacement d()\n{\n    extern float x = 1, y, z[2] = {1, 2};\n}\n") ==
          "test.sl:3:18: error: extern variable 'x' cannot have an initial value\n"
          "        extern float x = 1, y, z[2] = {1, 2};\n"
          "                     ^\n"
          "test.sl:3:28: error: extern variable 'z' cannot have an initial value\n"
          "        extern float x = 1, y, z[2] = {1, 2};\n"
          "                               ^\n");
}

TEST_CASE("preprocessor directives", "[lang]") {
    CHECK(Errors("#include \"noise.h\"\n  #  ifdef BMRT\ndisplacement d() {}\n") ==
          "test.sl:1:1: error: preprocessor directives are not supported yet\n"
          "    #include \"noise.h\"\n"
          "    ^\n"
          "test.sl:2:3: error: preprocessor directives are not supported yet\n"
          "      #  ifdef BMRT\n"
          "      ^\n");
}

TEST_CASE("missing shader body", "[lang]") {
    CHECK(Errors("displacement d(float Km = 1)\n") ==
          "test.sl:1:29: error: syntax error, unexpected end of file, expecting '{'\n"
          "    displacement d(float Km = 1)\n"
          "                                ^\n");
}

TEST_CASE("bad parameter syntax", "[lang]") {
    CHECK(Errors("displacement d(float Km 1)\n{\n}\n") ==
          "test.sl:1:25: error: syntax error, unexpected number, expecting ')'\n"
          "    displacement d(float Km 1)\n"
          "                            ^\n");
    CHECK(Errors("displacement d(Km = 1) {}\n") ==
          "test.sl:1:16: error: syntax error, unexpected identifier\n"
          "    displacement d(Km = 1) {}\n"
          "                   ^\n");
}

TEST_CASE("a file without a shader", "[lang]") {
    CHECK(Errors("") == "test.sl:1:1: error: no shader definition in file\n");
    CHECK(Errors("// nothing here\n") ==
          "test.sl:1:1: error: no shader definition in file\n"
          "    // nothing here\n"
          "    ^\n");
}

TEST_CASE("nesting limits", "[lang]") {
    // The nesting limit (1000) lowered to 256 for brackets, so the lines stay short.
    std::optional<affray::test::ScopedLimit> lowered(std::in_place, affray::diag::Limit::Nesting, 256);
    std::string parens = "displacement d() { x = " + std::string(300, '(') + "1" + std::string(300, ')') + "; }";
    CHECK(Errors(parens) ==
          "test.sl:1:279: error: nesting too deep: more than 256 open parentheses, brackets and "
          "braces (limit nesting = 256; raise it with --limit nesting=N)\n"
          "    " +
              parens +
              "\n"
              "    " +
              std::string(278, ' ') + "^\n");

    // Brackets count as well: the body's '{' and 256 '[' of `a[a[a[...]]]` are one too many.
    std::string brackets = "displacement d() { x = ";
    for (int i = 0; i < 300; ++i) brackets += "a[";
    brackets += "1" + std::string(300, ']') + "; }";
    CHECK(Errors(brackets) ==
          "test.sl:1:535: error: nesting too deep: more than 256 open parentheses, brackets and "
          "braces (limit nesting = 256; raise it with --limit nesting=N)\n"
          "    " +
              brackets +
              "\n"
              "    " +
              std::string(534, ' ') + "^\n");

    lowered.reset();  // the default, 1000, for the depth of trees
    std::string minus = "displacement d() {\nx = ";
    for (int i = 0; i < 1200; ++i) minus += "- ";
    minus += "1;\n}\n";
    CHECK(Errors(minus) ==
          "test.sl:2:405: error: expression too complex: nested more than 1000 levels deep (limit nesting = 1000; "
          "raise it with --limit nesting=N)\n"
          "    " +
              minus.substr(19, minus.size() - 22) +
              "\n"
              "    " +
              std::string(404, ' ') + "^\n");

    std::string ifs = "displacement d() {\n";
    for (int i = 0; i < 1001; ++i) ifs += "if (a)\n";
    ifs += "x = 1;\n}\n";
    CHECK(Errors(ifs) ==
          "test.sl:3:1: error: statements nested more than 1000 levels deep (limit nesting = 1000; raise it with "
          "--limit nesting=N)\n"
          "    if (a)\n"
          "    ^\n");
}

TEST_CASE("recovery reports several errors in one run", "[lang]") {
    CHECK(Errors("displacement d()\n{\n    x = 1 +;\n    y = (2, 3, 4, 5);\n    z = 1\n}\n"
                 "bogus;\nsurface s() { Ci = 1 }\n") ==
          "test.sl:3:12: error: syntax error, unexpected ';'\n"
          "        x = 1 +;\n"
          "               ^\n"
          "test.sl:4:9: error: a tuple must have 3 or 16 components\n"
          "        y = (2, 3, 4, 5);\n"
          "            ^\n"
          "test.sl:6:1: error: syntax error, unexpected '}', expecting ';'\n"
          "    }\n"
          "    ^\n"
          "test.sl:7:1: error: syntax error, unexpected identifier\n"
          "    bogus;\n"
          "    ^\n"
          "test.sl:8:22: error: syntax error, unexpected '}', expecting ';'\n"
          "    surface s() { Ci = 1 }\n"
          "                         ^\n");
    // The statements around the errors are still there.
    Parsed p = Run("displacement d() { a = 1; b = ; c = 2; }");
    REQUIRE(p.unit.shaders.size() == 1);
    CHECK(ToString(p.unit.shaders[0]) == "(displacement d (params) (body (= a 1) (empty) (= c 2)))");
}

TEST_CASE("loop levels and line markers in messages", "[lang]") {
    CHECK(Errors("displacement d()\n{\n    while (1) { break 0; }\n}\n") ==
          "test.sl:3:23: error: the loop level must be a positive integer\n"
          "        while (1) { break 0; }\n"
          "                          ^\n");
    // After a marker, lines are numbered from it; Diagnostics shows the text of that line of
    // this file, and here there is none.
    CHECK(Errors("# 20 \"wave.sl\"\ndisplacement d() { x = ; }\n") ==
          "test.sl:20:24: error: syntax error, unexpected ';'\n");
}

TEST_CASE("garbage bytes never crash", "[lang]") {
    CHECK(Errors("\x7F"
                 "ELF\x02") ==
          // The source line escapes what cannot print; the caret lines up with it as printed.
          "test.sl:1:1: error: invalid character '\\x7F'\n"
          "    \\x7fELF\\x02\n"
          "    ^\n"
          "test.sl:1:5: error: invalid character '\\x02'\n"
          "    \\x7fELF\\x02\n"
          "           ^\n");

    std::mt19937 rng(42);
    const char* pieces[] = {
        "displacement", "d",     "(",      ")",     "{",  "}",    ";",      ",",      "=", "+", ".",
        "float",        "point", "\"s\"",  "1.5",   "if", "else", "for",    "return", "?", ":", "/*",
        "//",           "\n",    "#",      "@",     "\"", "1e",   "matrix", "\xFF",   "x", "[", "]",
        "extern",       "void",  "output", "{1, 2}"};
    for (int i = 0; i < 300; ++i) {
        std::string text;
        int n = static_cast<int>(rng() % 50);
        for (int k = 0; k < n; ++k) {
            if (rng() % 4 == 0)
                text += static_cast<char>(rng() % 256);
            else
                text += std::string(pieces[rng() % std::size(pieces)]) + " ";
        }
        Parsed p = Run(text);
        // Every failure is reported: no diagnostics means a shader was found.
        CHECK((p.errorCount > 0 || !p.unit.shaders.empty()));
        for (const ShaderDef& s : p.unit.shaders) CHECK(!ToString(s).empty());
        for (const std::shared_ptr<FunctionDef>& f : p.unit.functions) CHECK(!ToString(*f).empty());
    }
}

TEST_CASE("many errors stop at the diagnostics cap", "[lang]") {
    Parsed p = Run(std::string(1000, '@'));
    CHECK(p.errorCount == Diagnostics::kMaxErrors + 1);
    CHECK(p.errors.substr(p.errors.rfind("test.sl: ")) == "test.sl: error: too many errors (51), stopping after 50\n");
}

}  // namespace affray::lang
