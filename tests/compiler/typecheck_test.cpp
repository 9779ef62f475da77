// tests/compiler/typecheck_test.cpp: the type rules (compiler/typecheck.h) on their own. The
// messages a shader gets for the same mistakes, with their locations and order, are pinned by
// tests/golden (diag_*.sl).
#include <catch2/catch.hpp>

#include "compiler/typecheck.h"

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
