// tests/compiler/typecheck_test.cpp: the type rules (compiler/typecheck.h) on their own, and the
// typed AST the typing pass records for a parsed shader. The messages a shader gets for the same
// mistakes, with their locations and order, are pinned by tests/golden (diag_*.sl).
#include <catch2/catch.hpp>

#include <filesystem>
#include <functional>

#include "compiler/lowerer.h"
#include "compiler/typecheck.h"
#include "lang/parse.h"
#include "tests/test_util.h"

using namespace affray;
using namespace affray::compiler;
using lang::AssignOp;
using lang::BinaryOp;

TEST_CASE("arithmetic: result types and the mixes it refuses", "[compiler][typecheck]") {
    CHECK(BinaryType(BinaryOp::Add, Type::Float, Type::Float).type == Type::Float);
    CHECK(BinaryType(BinaryOp::Mul, Type::Float, Type::Point).type == Type::Point);
    CHECK(BinaryType(BinaryOp::Sub, Type::Normal, Type::Float).type == Type::Normal);
    // Point, vector and normal mix; the first triple names the result.
    CHECK(BinaryType(BinaryOp::Add, Type::Point, Type::Vector).type == Type::Point);
    // A comparison is the float 1 or 0 in arithmetic, as in C.
    CHECK(BinaryType(BinaryOp::Add, Type::Bool, Type::Float).type == Type::Float);
    CHECK(BinaryType(BinaryOp::Dot, Type::Vector, Type::Color).type == Type::Float);
    CHECK(BinaryType(BinaryOp::Cross, Type::Point, Type::Normal).type == Type::Vector);
    CHECK(BinaryType(BinaryOp::Div, Type::Matrix, Type::Float).type == Type::Matrix);
    CHECK(BinaryType(BinaryOp::Add, Type::Color, Type::Point).error ==
          "invalid operands to '+' (color and point): a color does not combine with a point, vector or normal");
    CHECK(BinaryType(BinaryOp::Cross, Type::Color, Type::Color).error ==
          "invalid operands to '^' (color and color): '^' is the cross product of two vectors");
    CHECK(BinaryType(BinaryOp::Dot, Type::Float, Type::Point).error ==
          "invalid operands to '.' (float and point): '.' is the dot product of two triples");
    CHECK(BinaryType(BinaryOp::Add, Type::Matrix, Type::Float).error ==
          "invalid operands to '+' (matrix and float): a matrix only multiplies or divides a matrix or a float "
          "(transform() applies it to a point)");
    CHECK(BinaryType(BinaryOp::Mul, Type::Matrix, Type::Point).ok() == false);
    // A boolean operand is named as the float it becomes.
    CHECK(BinaryType(BinaryOp::Add, Type::Bool, Type::String).error == "invalid operands to '+' (float and string)");
    CHECK(NegateType(Type::Bool).type == Type::Float);
    CHECK(NegateType(Type::Color).type == Type::Color);
    CHECK(NegateType(Type::Matrix).error == "invalid operand to unary '-' (matrix)");
}

TEST_CASE("comparisons and conditions", "[compiler][typecheck]") {
    CHECK(BinaryType(BinaryOp::Less, Type::Float, Type::Bool).type == Type::Bool);
    CHECK(BinaryType(BinaryOp::Equal, Type::Point, Type::Vector).type == Type::Bool);
    CHECK(BinaryType(BinaryOp::Equal, Type::String, Type::String).type == Type::Bool);
    CHECK(BinaryType(BinaryOp::And, Type::Bool, Type::Float).type == Type::Bool);
    // Operands of comparisons are named as written: a boolean stays one.
    CHECK(BinaryType(BinaryOp::And, Type::Bool, Type::Point).error ==
          "invalid operands to '&&' (boolean and point): '&&' combines conditions");
    CHECK(BinaryType(BinaryOp::Less, Type::String, Type::String).error ==
          "invalid operands to '<' (string and string): strings compare only with == and != to strings");
    CHECK(BinaryType(BinaryOp::Less, Type::Point, Type::Point).error ==
          "invalid operands to '<' (point and point): only floats are ordered");
    CHECK(BinaryType(BinaryOp::NotEqual, Type::Color, Type::Normal).error ==
          "invalid operands to '!=' (color and normal): a color does not compare with a point, vector or normal");
    CHECK(BinaryType(BinaryOp::Equal, Type::Matrix, Type::Point).error ==
          "invalid operands to '==' (matrix and point): a matrix compares with a matrix or a float");
    CHECK(ConditionType(Type::Float).ok());
    CHECK(ConditionType(Type::Bool).ok());
    CHECK(ConditionType(Type::Point).error == "a condition must be a comparison or a float, not a point");
}

TEST_CASE("?:, triples, matrices, casts and conversions", "[compiler][typecheck]") {
    CHECK(TernaryType(Type::Bool, Type::Bool).type == Type::Bool);
    CHECK(TernaryType(Type::Float, Type::Color).type == Type::Color);
    CHECK(TernaryType(Type::Vector, Type::Bool).type == Type::Vector);
    CHECK(TernaryType(Type::String, Type::String).type == Type::String);
    CHECK(TernaryType(Type::Color, Type::Point).error ==
          "the two results of '?:' have incompatible types (color and point)");
    CHECK(TernaryType(Type::String, Type::Float).ok() == false);
    // A comparison is not a triple's component, but it is a matrix entry.
    CHECK(TripleComponentType(Type::Bool).error == "a triple's components must be floats, got a boolean");
    CHECK(MatrixEntryType(Type::Bool).ok());
    CHECK(MatrixEntryType(Type::Color).error == "a matrix's entries must be floats, got a color");
    CHECK(ConvertType(Type::Bool, Type::Float, "x").type == Type::Float);
    CHECK(ConvertType(Type::Float, Type::Matrix, "x").type == Type::Matrix);
    CHECK(ConvertType(Type::Normal, Type::Point, "x").type == Type::Point);
    CHECK(ConvertType(Type::Color, Type::Point, "point variable 'q'").error ==
          "cannot assign a color to point variable 'q'");
    CHECK(ConvertType(Type::Point, Type::Float, "the return value").error ==
          "cannot assign a point to the return value");
    CHECK(CompoundAssignType(AssignOp::AddAssign, Type::Point, Type::Float, "w").type == Type::Point);
    CHECK(CompoundAssignType(AssignOp::MulAssign, Type::Matrix, Type::Matrix, "w").type == Type::Matrix);
    CHECK(CompoundAssignType(AssignOp::AddAssign, Type::Matrix, Type::Float, "w").error ==
          "invalid operands to '+=' (matrix and float)");
    CHECK(CompoundAssignType(AssignOp::AddAssign, Type::Float, Type::Vector, "float variable 'f'").error ==
          "cannot assign a vector to float variable 'f'");
    CHECK(CompoundAssignType(AssignOp::SubAssign, Type::Color, Type::Point, "c").error == "cannot assign a point to c");
    CHECK(CastType(Type::Float, Type::Color, false).type == Type::Color);
    CHECK(CastType(Type::Color, Type::Color, true).type == Type::Color);
    CHECK(CastType(Type::Vector, Type::Point, false).type == Type::Point);
    CHECK(CastType(Type::Float, Type::Matrix, true).type == Type::Matrix);
    CHECK(CastType(Type::Point, Type::Float, false).error == "cannot cast a point to float");
    CHECK(CastType(Type::String, Type::Point, true).error == "cannot cast a string to point");
    CHECK(CastType(Type::Color, Type::Matrix, false).error == "cannot cast a color to matrix");
}

namespace {
/// Parses `text` (one shader, no errors) and types it; `visit` gets the typed AST and the unit.
void WithTypes(const std::string& text,
               const std::function<void(const TypedShader&, const lang::TranslationUnit&)>& visit) {
    lang::SourceFile file("t.sl", text);
    lang::Diagnostics diags(file);
    lang::TranslationUnit unit = lang::Parse(diags);
    REQUIRE_FALSE(diags.hasErrors());
    REQUIRE(unit.shaders.size() == 1);
    visit(Typecheck(unit.shaders[0], unit.functions), unit);
}

/// The expression of statement `i` of the shader's body (an expression statement).
const lang::Expr& Statement(const lang::TranslationUnit& unit, size_t i) { return *unit.shaders[0].body.at(i)->expr; }
}  // namespace

TEST_CASE("the typed AST: names resolved, every expression typed", "[compiler][typecheck]") {
    WithTypes(
        "displacement d(float Km = 1; string space = \"object\") {\n"
        "  vector offset = 0;\n"
        "  float w[3] = {1, 2, 3};\n"
        "  offset += Km * N;\n"
        "  P + offset;\n"
        "  w[1] > 0 ? Km : PI;\n"
        "  space == \"world\";\n"
        "  (Km, u, v) . normal(1);\n"
        "}\n",
        [](const TypedShader& typed, const lang::TranslationUnit& unit) {
            const lang::Expr& assign = Statement(unit, 2);
            CHECK(typed.TypeOf(assign) == Type::Vector);
            CHECK(typed.Find(assign)->symbol == SymbolKind::Local);
            const lang::Expr& product = *assign.args[0];
            CHECK(typed.TypeOf(product) == Type::Normal);
            CHECK(typed.Find(*product.args[0])->symbol == SymbolKind::Parameter);
            CHECK(typed.Find(*product.args[1])->symbol == SymbolKind::Global);
            // point + vector: the first triple's type.
            CHECK(typed.TypeOf(Statement(unit, 3)) == Type::Point);
            const lang::Expr& choice = Statement(unit, 4);
            CHECK(typed.TypeOf(choice) == Type::Float);
            CHECK(typed.TypeOf(*choice.args[0]) == Type::Bool);
            CHECK(typed.Find(*choice.args[0]->args[0]->args[0])->arraySize == 3);
            CHECK(typed.TypeOf(*choice.args[0]->args[0]) == Type::Float);  // an element
            CHECK(typed.TypeOf(Statement(unit, 5)) == Type::Bool);
            CHECK(typed.TypeOf(Statement(unit, 6)) == Type::Float);
        });
}

TEST_CASE("the typed AST: user functions, scopes, and what is left untyped", "[compiler][typecheck]") {
    WithTypes(
        "color tint(float x) { return color(x); }\n"
        "displacement d() {\n"
        "  tint(u);\n"
        "  { point q = P; }\n"
        "  q;\n"
        "  color P = 0;\n"
        "  P;\n"
        "  sin(u);\n"
        "  N + color(1);\n"
        "  float inner() { return 1; }\n"
        "  inner();\n"
        "}\n",
        [](const TypedShader& typed, const lang::TranslationUnit& unit) {
            const lang::Expr& call = Statement(unit, 0);
            CHECK(typed.TypeOf(call) == Type::Color);
            CHECK(typed.Find(call)->callee == unit.functions[0].get());
            CHECK(typed.TypeOf(*call.args[0]) == Type::Float);
            // The function's own body is typed too, in its own scope.
            const lang::Expr& returned = *unit.functions[0]->body[0]->expr;
            CHECK(typed.TypeOf(returned) == Type::Color);
            CHECK(typed.Find(*returned.args[0])->symbol == SymbolKind::Parameter);
            // A block's variable is gone after it; a local shadows a global.
            CHECK(typed.Find(Statement(unit, 2)) == nullptr);
            CHECK(typed.TypeOf(Statement(unit, 4)) == Type::Color);
            // A built-in's result is the lowering's to choose (by overload); an ill-typed
            // expression has no type.
            CHECK(typed.Find(Statement(unit, 5)) == nullptr);
            CHECK(typed.TypeOf(*Statement(unit, 5).args[0]) == Type::Float);
            CHECK(typed.Find(Statement(unit, 6)) == nullptr);
            CHECK(typed.TypeOf(Statement(unit, 8)) == Type::Float);
        });
}

TEST_CASE("the typed AST gives every expression of the suite and the library the lowering's type",
          "[compiler][typecheck]") {
    // The checker walks trees the lowering then rejects too (tests/golden/diag_*.sl): redefined
    // names, unknown ones, missing arms. Wherever it gives a type, the lowering (which unrolls,
    // inlines and folds) must get a value of that type: the condition for the lowering to read
    // types from the typed AST instead of its values.
    int shaders = 0;
    long agree = 0;
    for (const std::string dir : {"/tests/golden", "/tests/corpus", "/shaders"}) {
        for (const auto& entry : std::filesystem::directory_iterator(test::SourceDir() + dir)) {
            if (entry.path().extension() != ".sl") continue;
            lang::SourceFile file("", "");
            REQUIRE(lang::SourceFile::Load(entry.path().string(), &file, nullptr));
            lang::Diagnostics diags(file);
            const lang::TranslationUnit unit = lang::PreprocessAndParse(diags, {});
            if (diags.hasErrors() || unit.shaders.empty()) continue;
            INFO(entry.path().string());
            const TypedShader typed = Typecheck(unit.shaders[0], unit.functions);
            std::vector<std::string> differ;
            LowerObserved(unit, diags, [&](const lang::Expr& e, const Value& v) {
                const ExprType* t = typed.Find(e);
                if (!t) return;
                ++agree;
                if (t->type != v.type)
                    differ.push_back(std::to_string(e.loc.line) + ": " + lang::ToString(e) + " is " +
                                     ToString(t->type) + ", lowered as " + ToString(v.type));
            });
            CHECK(differ == std::vector<std::string>{});
            ++shaders;
        }
    }
    CHECK(shaders > 100);
    CHECK(agree > 10000);
}
