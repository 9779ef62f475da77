// lang/ast.h: the syntax tree the parser builds and the compiler consumes.
// Nodes are plain tagged structs owning their children; the parser's actions only build them
// (no checking here: names, types and overloads are the compiler's job). Every node keeps the
// location of the token that best explains an error about it (an operator, a name, a keyword).
// To add a construct: add a kind, say in a comment which fields it uses, build it in parser.y,
// and handle it in compiler/typecheck.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "lang/source.h"

namespace affray::lang {

/// Types as written in source. The parser accepts `void` wherever a type may be written (a
/// declaration, a parameter, a cast, a function's return type) and leaves rejecting void
/// variables to the compiler.
enum class TypeName { Float, Point, Vector, Normal, Color, String, Void, Matrix };
const char* ToString(TypeName t);

enum class UnaryOp { Negate, Not };
enum class BinaryOp { Add, Sub, Mul, Div, Dot, Cross, Less, LessEq, Greater, GreaterEq, Equal, NotEqual, And, Or };
enum class AssignOp { Assign, AddAssign, SubAssign, MulAssign, DivAssign };
const char* ToString(UnaryOp op);
const char* ToString(BinaryOp op);
const char* ToString(AssignOp op);

struct Expr;
using ExprPtr = std::unique_ptr<Expr>;

enum class ExprKind {
    Number,   // number
    String,   // text
    Ident,    // name
    Unary,    // unaryOp, args[0]
    Binary,   // binaryOp, args[0], args[1]
    Assign,   // assignOp, name (the target variable), args[0] (the value), and args[1] (the
              // index) when the target is an array element `name[args[1]]` (args.size() == 2)
    Call,     // name (the function), args
    Triple,   // args[0..2]: the parenthesised (a, b, c)
    Tuple16,  // args[0..15]: a parenthesised 16-tuple, a matrix in row-major order
    Cast,     // castType, castSpace (may be empty), args[0]: `point "space" expr`, `point(a,b,c)`
    Ternary,  // args[0] ? args[1] : args[2]
    Index,    // args[0][args[1]]: an array element; loc is the '['
};

struct Expr {
    ExprKind kind;
    SourceLoc loc;
    double number = 0;
    std::string text;  // String literal contents, without quotes and with escapes resolved
    std::string name;
    UnaryOp unaryOp = UnaryOp::Negate;
    BinaryOp binaryOp = BinaryOp::Add;
    AssignOp assignOp = AssignOp::Assign;
    TypeName castType = TypeName::Float;
    std::string castSpace;
    std::vector<ExprPtr> args;

    Expr(ExprKind k, SourceLoc l) : kind(k), loc(l) {}
};

/// Storage class written before a declaration's type.
enum class Detail { Default, Uniform, Varying };

/// One declared variable or parameter: `type name = init`, `type name[N] = {a, b, ...}`,
/// `extern type name`. In a unit parsed without errors: an init list only on a sized array, with
/// exactly arraySize items; a plain init never on an array; no initialiser on an extern or a
/// function parameter; arraySize 0 only on a function parameter or an extern.
struct VarDecl {
    TypeName type = TypeName::Float;
    Detail detail = Detail::Default;
    bool isOutput = false;
    bool isExtern = false;  // `extern type name`: a variable of an enclosing scope
    std::string name;
    SourceLoc loc;             // of the name
    int arraySize = -1;        // -1: not an array; 0: unsized `name[]`; N: `name[N]`
    ExprPtr init;              // `= expr`; may be null (always null if hasInitList)
    bool hasInitList = false;  // `= {a, b, ...}`
    std::vector<ExprPtr> initList;
};

struct Stmt;
using StmtPtr = std::unique_ptr<Stmt>;
struct FunctionDef;

enum class StmtKind {
    Expr,         // expr
    Decl,         // decls (all share one type, `float a = 1, b;`)
    Block,        // body
    Empty,        // a lone ';'
    If,           // expr (condition), body[0] (then), body[1] (else, optional)
    For,          // init, expr (condition), step, body[0]; init/expr/step may be null
    While,        // expr (condition), body[0]
    Return,       // expr (may be null)
    Break,        // level (1 unless written `break 2`)
    Continue,     // level
    FunctionDef,  // function: defined inside a shader's or a function's body; loc is its type
};

struct Stmt {
    StmtKind kind;
    SourceLoc loc;
    ExprPtr expr;
    std::vector<VarDecl> decls;
    std::vector<StmtPtr> body;
    ExprPtr init;
    ExprPtr step;
    int level = 1;
    std::shared_ptr<FunctionDef> function;

    Stmt(StmtKind k, SourceLoc l) : kind(k), loc(l) {}
};

enum class ShaderKind { Displacement, Surface, Light, Volume, Imager };
const char* ToString(ShaderKind k);

struct ShaderDef {
    ShaderKind kind = ShaderKind::Displacement;
    std::string name;
    SourceLoc loc;  // of the name
    std::vector<VarDecl> params;
    std::vector<StmtPtr> body;
};

/// A user function: `type name(params) { body }`. Parameters are written like a shader's
/// (`float a, b; output point p`) but have no defaults; `float a[]` leaves the size open.
struct FunctionDef {
    TypeName returnType = TypeName::Void;
    std::string name;
    SourceLoc loc;  // of the name
    std::vector<VarDecl> params;
    std::vector<StmtPtr> body;
};

/// Everything in one preprocessed source file. Shaders and top-level functions each keep their
/// source order; nested functions are statements (StmtKind::FunctionDef) of their enclosing body.
struct TranslationUnit {
    std::vector<ShaderDef> shaders;
    std::vector<std::shared_ptr<FunctionDef>> functions;
};

/// Prints a tree in a compact Lisp-like form, for tests and debugging:
/// e.g. `(+= P (* Km N))`. The format of every node is listed at the top of lang/ast.cpp.
std::string ToString(const Expr& e);
std::string ToString(const Stmt& s);
std::string ToString(const ShaderDef& s);
std::string ToString(const FunctionDef& f);

}  // namespace affray::lang
