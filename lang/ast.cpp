// lang/ast.cpp: printing syntax trees, for tests and debugging.
// Owns the one text form of the AST. It is a compact Lisp-like form on one line; tests compare
// against it, so change it only with them. Each node prints as:
//   Number      %g                          0.1   20   1e-05
//   String      "text", re-escaped          "shader"   "a\"b\n"
//   Ident       name                        P
//   Unary       (op a)                      (- a)   (! a)        (unary + is dropped)
//   Binary      (op a b)                    (+ a b)  (. a b) dot   (^ a b) cross   (&& a b)
//   Assign      (op name value)             (= x 1)   (+= P (* Km N))
//               (op ([] name i) value)      (= ([] a i) 1)   for an array element
//   Call        (call name args...)         (call noise P)
//   Triple      (triple a b c)              (triple 0 0 1)
//   Tuple16     (tuple16 a...)              (tuple16 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1)
//   Cast        (cast type ["space"] a)     (cast point "shader" (triple 1 2 3))
//   Ternary     (? cond a b)                (? c x y)
//   Index       ([] array index)            ([] a (+ i 1))
//   VarDecl     ([extern] [output] [uniform|varying] type name[[N]] [init])
//               with an array's size after its name and an init list in braces:
//               (float Km 0.1)   (float a[3] {1 2 3})   (output float f[])   (extern point P)
//   Stmt        Expr: the expression itself; Decl: (decl VarDecl...); Block: (block s...);
//               Empty: (empty); If: (if c then [else]); For: (for init cond step body) with an
//               absent part printed as (); While: (while c body); Return: (return [e]);
//               Break/Continue: (break) or (break N) when N is not 1; FunctionDef: the
//               FunctionDef.
//   ShaderDef   (kind name (params VarDecl...) (body s...))
//   FunctionDef (function type name (params VarDecl...) (body s...))
//               (function float f (params (float x) (output point p[])) (body (return x)))
// To add a node kind: add a case here and a line above.
#include <cstdio>

#include "lang/ast.h"

namespace affray::lang {

const char* ToString(TypeName t) {
    switch (t) {
        case TypeName::Float: return "float";
        case TypeName::Point: return "point";
        case TypeName::Vector: return "vector";
        case TypeName::Normal: return "normal";
        case TypeName::Color: return "color";
        case TypeName::String: return "string";
        case TypeName::Void: return "void";
        case TypeName::Matrix: return "matrix";
    }
    return "?";
}

const char* ToString(UnaryOp op) {
    switch (op) {
        case UnaryOp::Negate: return "-";
        case UnaryOp::Not: return "!";
    }
    return "?";
}

const char* ToString(BinaryOp op) {
    switch (op) {
        case BinaryOp::Add: return "+";
        case BinaryOp::Sub: return "-";
        case BinaryOp::Mul: return "*";
        case BinaryOp::Div: return "/";
        case BinaryOp::Dot: return ".";
        case BinaryOp::Cross: return "^";
        case BinaryOp::Less: return "<";
        case BinaryOp::LessEq: return "<=";
        case BinaryOp::Greater: return ">";
        case BinaryOp::GreaterEq: return ">=";
        case BinaryOp::Equal: return "==";
        case BinaryOp::NotEqual: return "!=";
        case BinaryOp::And: return "&&";
        case BinaryOp::Or: return "||";
    }
    return "?";
}

const char* ToString(AssignOp op) {
    switch (op) {
        case AssignOp::Assign: return "=";
        case AssignOp::AddAssign: return "+=";
        case AssignOp::SubAssign: return "-=";
        case AssignOp::MulAssign: return "*=";
        case AssignOp::DivAssign: return "/=";
    }
    return "?";
}

const char* ToString(ShaderKind k) {
    switch (k) {
        case ShaderKind::Displacement: return "displacement";
        case ShaderKind::Surface: return "surface";
        case ShaderKind::Light: return "light";
        case ShaderKind::Volume: return "volume";
        case ShaderKind::Imager: return "imager";
    }
    return "?";
}

namespace {

std::string Quoted(const std::string& text) {
    std::string out = "\"";
    for (char c : text) {
        unsigned char u = static_cast<unsigned char>(c);
        if (c == '"' || c == '\\') {
            out += '\\';
            out += c;
        } else if (c == '\n') {
            out += "\\n";
        } else if (c == '\t') {
            out += "\\t";
        } else if (u < 0x20 || u == 0x7f) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\x%02X", u);
            out += buf;
        } else {
            out += c;
        }
    }
    return out + "\"";
}

// "(head a b c)" from already printed parts.
std::string List(const std::string& head, const std::vector<std::string>& items) {
    std::string out = "(" + head;
    for (const std::string& item : items) out += " " + item;
    return out + ")";
}

std::string ToString(const VarDecl& v) {
    std::string out = "(";
    if (v.isExtern) out += "extern ";
    if (v.isOutput) out += "output ";
    if (v.detail == Detail::Uniform) out += "uniform ";
    if (v.detail == Detail::Varying) out += "varying ";
    out += ToString(v.type);
    out += ' ';
    out += v.name;
    if (v.arraySize > 0) out += "[" + std::to_string(v.arraySize) + "]";
    if (v.arraySize == 0) out += "[]";
    if (v.init) {
        out += ' ';
        out += ToString(*v.init);
    }
    if (v.hasInitList) {
        out += " {";
        for (size_t i = 0; i < v.initList.size(); ++i) {
            if (i > 0) out += ' ';
            out += v.initList[i] ? ToString(*v.initList[i]) : "()";
        }
        out += '}';
    }
    return out + ")";
}

std::string Maybe(const ExprPtr& e) { return e ? ToString(*e) : "()"; }
std::string Maybe(const StmtPtr& s) { return s ? ToString(*s) : "()"; }

std::string Params(const std::vector<VarDecl>& params) {
    std::vector<std::string> items;
    items.reserve(params.size());
    for (const VarDecl& v : params) items.push_back(ToString(v));
    return List("params", items);
}

std::string Body(const std::vector<StmtPtr>& body) {
    std::vector<std::string> items;
    items.reserve(body.size());
    for (const StmtPtr& s : body) items.push_back(Maybe(s));
    return List("body", items);
}

}  // namespace

std::string ToString(const Expr& e) {
    std::vector<std::string> args;
    for (const ExprPtr& a : e.args) args.push_back(Maybe(a));
    switch (e.kind) {
        case ExprKind::Number: {
            char buf[32];
            std::snprintf(buf, sizeof buf, "%g", e.number);
            return buf;
        }
        case ExprKind::String: return Quoted(e.text);
        case ExprKind::Ident: return e.name;
        case ExprKind::Unary: return List(ToString(e.unaryOp), args);
        case ExprKind::Binary: return List(ToString(e.binaryOp), args);
        case ExprKind::Assign: {
            std::string target = e.name;
            if (args.size() == 2) target = List("[]", {target, args[1]});
            return List(ToString(e.assignOp), {target, args.empty() ? "()" : args[0]});
        }
        case ExprKind::Call: args.insert(args.begin(), e.name); return List("call", args);
        case ExprKind::Triple: return List("triple", args);
        case ExprKind::Tuple16: return List("tuple16", args);
        case ExprKind::Cast:
            if (!e.castSpace.empty()) args.insert(args.begin(), Quoted(e.castSpace));
            return List(std::string("cast ") + ToString(e.castType), args);
        case ExprKind::Ternary: return List("?", args);
        case ExprKind::Index: return List("[]", args);
    }
    return "(?)";
}

std::string ToString(const Stmt& s) {
    std::vector<std::string> body;
    for (const StmtPtr& b : s.body) body.push_back(Maybe(b));
    switch (s.kind) {
        case StmtKind::Expr: return Maybe(s.expr);
        case StmtKind::Decl: {
            std::vector<std::string> decls;
            for (const VarDecl& v : s.decls) decls.push_back(ToString(v));
            return List("decl", decls);
        }
        case StmtKind::Block: return List("block", body);
        case StmtKind::Empty: return "(empty)";
        case StmtKind::If: body.insert(body.begin(), Maybe(s.expr)); return List("if", body);
        case StmtKind::For:
            body.insert(body.begin(), {Maybe(s.init), Maybe(s.expr), Maybe(s.step)});
            return List("for", body);
        case StmtKind::While: body.insert(body.begin(), Maybe(s.expr)); return List("while", body);
        case StmtKind::Return: return s.expr ? List("return", {ToString(*s.expr)}) : "(return)";
        case StmtKind::Break:
        case StmtKind::Continue: {
            std::string head = s.kind == StmtKind::Break ? "break" : "continue";
            return s.level == 1 ? "(" + head + ")" : List(head, {std::to_string(s.level)});
        }
        case StmtKind::FunctionDef: return s.function ? ToString(*s.function) : "(function)";
    }
    return "(?)";
}

std::string ToString(const ShaderDef& s) {
    return List(std::string(ToString(s.kind)) + " " + s.name, {Params(s.params), Body(s.body)});
}

std::string ToString(const FunctionDef& f) {
    return List(std::string("function ") + ToString(f.returnType) + " " + f.name, {Params(f.params), Body(f.body)});
}

}  // namespace affray::lang
