// lang/parse.cpp: Parse(), and the node builders the grammar's actions call.
// Owns the checks a context-free grammar cannot say well: assignment targets, tuple sizes,
// `break N` levels, array sizes and initialisers, what each kind of declaration may have
// (defaults, unsized arrays, initialisers on externs), and the depth limits that keep every
// later recursive pass (printing, destruction, the compiler) within the stack. Builders never
// return null, so a tree built while recovering from errors is still safe to walk.
#include <algorithm>
#include <cmath>
#include <exception>
#include <map>
#include <memory>
#include <new>
#include <set>

#include "lang/parse.h"
#include "parser.hh"

namespace affray::lang {

namespace {

// Beyond the source-bytes limit's maximum the lexer's int lengths would be at risk.
size_t MaxSourceBytes() { return static_cast<size_t>(diag::LimitValue(diag::Limit::SourceBytes)); }

}  // namespace

// --- Diagnostics and limits ----------------------------------------------------------------------

void ParseContext::Error(SourceLoc loc, std::string message) {
    if (m_stopped) return;
    m_diags.error(loc, std::move(message));
    // Past the cap nothing more is shown, so stop rather than grind through garbage.
    if (m_diags.errorCount() > Diagnostics::kMaxErrors) m_stopped = true;
}

ExprNode ParseContext::Finish(ExprPtr e, int depth) {
    if (depth > m_maxNesting) {
        if (!m_reportedExprDepth)
            Error(e->loc, "expression too complex: nested more than " + std::to_string(m_maxNesting) + " levels deep " +
                              diag::LimitNote(diag::Limit::Nesting));
        m_reportedExprDepth = true;
        // Replace the subtree by a leaf so that nothing deeper is ever built.
        e = std::make_unique<Expr>(ExprKind::Number, e->loc);
        depth = 1;
    }
    return {std::move(e), depth};
}

StmtNode ParseContext::Finish(StmtPtr s, int depth) {
    if (depth > m_maxNesting) {
        if (!m_reportedStmtDepth)
            Error(s->loc, "statements nested more than " + std::to_string(m_maxNesting) + " levels deep " +
                              diag::LimitNote(diag::Limit::Nesting));
        m_reportedStmtDepth = true;
        s = std::make_unique<Stmt>(StmtKind::Empty, s->loc);
        depth = 1;
    }
    return {std::move(s), depth};
}

// --- Expressions -----------------------------------------------------------------------------

ExprNode ParseContext::Number(SourceLoc loc, double value) {
    auto e = std::make_unique<Expr>(ExprKind::Number, loc);
    e->number = value;
    return Finish(std::move(e), 1);
}

ExprNode ParseContext::String(SourceLoc loc, std::string text) {
    auto e = std::make_unique<Expr>(ExprKind::String, loc);
    e->text = std::move(text);
    return Finish(std::move(e), 1);
}

ExprNode ParseContext::Ident(SourceLoc loc, std::string name) {
    auto e = std::make_unique<Expr>(ExprKind::Ident, loc);
    e->name = std::move(name);
    return Finish(std::move(e), 1);
}

ExprNode ParseContext::Unary(UnaryOp op, SourceLoc loc, ExprNode operand) {
    auto e = std::make_unique<Expr>(ExprKind::Unary, loc);
    e->unaryOp = op;
    e->args.push_back(std::move(operand.expr));
    return Finish(std::move(e), 1 + operand.depth);
}

ExprNode ParseContext::Binary(BinaryOp op, SourceLoc loc, ExprNode lhs, ExprNode rhs) {
    auto e = std::make_unique<Expr>(ExprKind::Binary, loc);
    e->binaryOp = op;
    e->args.push_back(std::move(lhs.expr));
    e->args.push_back(std::move(rhs.expr));
    return Finish(std::move(e), 1 + std::max(lhs.depth, rhs.depth));
}

ExprNode ParseContext::Assign(AssignOp op, SourceLoc loc, ExprNode target, ExprNode value) {
    Expr& t = *target.expr;
    bool element = t.kind == ExprKind::Index && t.args[0]->kind == ExprKind::Ident;
    if (t.kind != ExprKind::Ident && !element) {
        Error(loc, "left side of assignment must be a variable or an array element");
        return value;
    }
    auto e = std::make_unique<Expr>(ExprKind::Assign, loc);
    e->assignOp = op;
    e->name = std::move(element ? t.args[0]->name : t.name);
    e->args.push_back(std::move(value.expr));
    if (element) e->args.push_back(std::move(t.args[1]));
    // The target's depth bounds its index's.
    return Finish(std::move(e), 1 + std::max(value.depth, target.depth));
}

ExprNode ParseContext::Call(SourceLoc loc, std::string name, ExprList args) {
    auto e = std::make_unique<Expr>(ExprKind::Call, loc);
    e->name = std::move(name);
    e->args = std::move(args.items);
    return Finish(std::move(e), 1 + args.depth);
}

ExprNode ParseContext::Tuple(SourceLoc loc, ExprNode first, ExprList rest) {
    size_t count = rest.items.size() + 1;
    if (count != 3 && count != 16) {
        Error(loc, "a tuple must have 3 or 16 components");
        return Number(loc, 0);
    }
    auto e = std::make_unique<Expr>(count == 3 ? ExprKind::Triple : ExprKind::Tuple16, loc);
    e->args.push_back(std::move(first.expr));
    for (ExprPtr& r : rest.items) e->args.push_back(std::move(r));
    return Finish(std::move(e), 1 + std::max(first.depth, rest.depth));
}

ExprNode ParseContext::Index(SourceLoc loc, ExprNode array, ExprNode index) {
    auto e = std::make_unique<Expr>(ExprKind::Index, loc);
    e->args.push_back(std::move(array.expr));
    e->args.push_back(std::move(index.expr));
    return Finish(std::move(e), 1 + std::max(array.depth, index.depth));
}

ExprNode ParseContext::Cast(SourceLoc loc, TypeName type, std::string space, ExprNode operand) {
    auto e = std::make_unique<Expr>(ExprKind::Cast, loc);
    e->castType = type;
    e->castSpace = std::move(space);
    e->args.push_back(std::move(operand.expr));
    return Finish(std::move(e), 1 + operand.depth);
}

ExprNode ParseContext::Ternary(SourceLoc loc, ExprNode cond, ExprNode yes, ExprNode no) {
    auto e = std::make_unique<Expr>(ExprKind::Ternary, loc);
    e->args.push_back(std::move(cond.expr));
    e->args.push_back(std::move(yes.expr));
    e->args.push_back(std::move(no.expr));
    return Finish(std::move(e), 1 + std::max({cond.depth, yes.depth, no.depth}));
}

void ParseContext::Append(ExprList& list, ExprNode e) {
    list.items.push_back(std::move(e.expr));
    list.depth = std::max(list.depth, e.depth);
}

// --- Statements ------------------------------------------------------------------------------
// A statement's depth counts statements only: its expressions are bounded on their own.

StmtNode ParseContext::Simple(StmtKind kind, SourceLoc loc, ExprNode expr) {
    auto s = std::make_unique<Stmt>(kind, loc);
    s->expr = std::move(expr.expr);
    return Finish(std::move(s), 1);
}

StmtNode ParseContext::Decl(SourceLoc loc, std::vector<VarDecl> decls) {
    RequireSizes(decls);
    auto s = std::make_unique<Stmt>(StmtKind::Decl, loc);
    s->decls = std::move(decls);
    return Finish(std::move(s), 1);
}

StmtNode ParseContext::Block(SourceLoc loc, StmtList body) {
    auto s = std::make_unique<Stmt>(StmtKind::Block, loc);
    s->body = std::move(body.items);
    return Finish(std::move(s), 1 + body.depth);
}

StmtNode ParseContext::If(SourceLoc loc, ExprNode cond, StmtNode yes, StmtNode no) {
    auto s = std::make_unique<Stmt>(StmtKind::If, loc);
    s->expr = std::move(cond.expr);
    s->body.push_back(std::move(yes.stmt));
    if (no.stmt) s->body.push_back(std::move(no.stmt));
    return Finish(std::move(s), 1 + std::max(yes.depth, no.depth));
}

StmtNode ParseContext::For(SourceLoc loc, ExprNode init, ExprNode cond, ExprNode step, StmtNode body) {
    auto s = std::make_unique<Stmt>(StmtKind::For, loc);
    s->init = std::move(init.expr);
    s->expr = std::move(cond.expr);
    s->step = std::move(step.expr);
    s->body.push_back(std::move(body.stmt));
    return Finish(std::move(s), 1 + body.depth);
}

StmtNode ParseContext::While(SourceLoc loc, ExprNode cond, StmtNode body) {
    auto s = std::make_unique<Stmt>(StmtKind::While, loc);
    s->expr = std::move(cond.expr);
    s->body.push_back(std::move(body.stmt));
    return Finish(std::move(s), 1 + body.depth);
}

StmtNode ParseContext::Jump(StmtKind kind, SourceLoc loc, int level) {
    auto s = std::make_unique<Stmt>(kind, loc);
    s->level = level;
    return Finish(std::move(s), 1);
}

void ParseContext::Append(StmtList& list, StmtNode s) {
    list.items.push_back(std::move(s.stmt));
    list.depth = std::max(list.depth, s.depth);
}

int ParseContext::JumpLevel(SourceLoc loc, double value) {
    if (value >= 1 && value <= 1000000 && value == std::floor(value)) return static_cast<int>(value);
    Error(loc, "the loop level must be a positive integer");
    return 1;
}

// --- Declarations, shaders and functions ----------------------------------------------------

int ParseContext::ArraySize(SourceLoc loc, double value) {
    if (value >= 1 && value <= 1000000 && value == std::floor(value)) return static_cast<int>(value);
    Error(loc, "the array size must be a positive integer");
    return 1;
}

Init ParseContext::ExprInit(SourceLoc loc, ExprNode expr) {
    Init init;
    init.loc = loc;
    init.expr = std::move(expr);
    return init;
}

Init ParseContext::ListInit(SourceLoc loc, ExprList list, bool bad) {
    Init init;
    init.loc = loc;
    init.list = std::move(list);
    init.isList = true;
    init.bad = bad;
    return init;
}

void ParseContext::AddVar(std::vector<VarDecl>& list, SourceLoc loc, std::string name, int arraySize, Init init) {
    VarDecl v;
    v.name = std::move(name);
    v.loc = loc;
    v.arraySize = arraySize;
    v.init = std::move(init.expr.expr);
    v.hasInitList = init.isList;
    v.initList = std::move(init.list.items);
    // A bad list was reported where it went wrong; its (partial) contents say nothing more.
    if (v.hasInitList && !init.bad) {
        if (v.arraySize < 0)
            Error(init.loc, "'" + v.name + "' is not an array; only an array takes a list in braces");
        else if (v.arraySize > 0 && v.initList.size() != static_cast<size_t>(v.arraySize))
            Error(init.loc, "array '" + v.name + "' of size " + std::to_string(v.arraySize) + " has " +
                                std::to_string(v.initList.size()) + " initial values");
    } else if (v.init && v.arraySize >= 0) {
        Error(init.loc, "the initial values of array '" + v.name + "' must be a list in braces, as in {1, 2, 3}");
    }
    list.push_back(std::move(v));
}

std::vector<VarDecl> ParseContext::Typed(std::vector<VarDecl> list, TypeName type, Detail detail, bool output) {
    for (VarDecl& v : list) {
        v.type = type;
        v.detail = detail;
        v.isOutput = output;
    }
    return list;
}

std::vector<VarDecl> ParseContext::Extern(std::vector<VarDecl> list) {
    for (VarDecl& v : list) {
        v.isExtern = true;
        if (v.init || v.hasInitList) {
            Error(v.loc, "extern variable '" + v.name + "' cannot have an initial value");
            v.init = nullptr;
            v.hasInitList = false;
            v.initList.clear();
        }
    }
    return list;
}

void ParseContext::RequireSizes(const std::vector<VarDecl>& decls) {
    for (const VarDecl& v : decls)
        if (v.arraySize == 0 && !v.isExtern)
            Error(v.loc, "array '" + v.name + "' needs a size (only function parameters and externs may omit it)");
}

std::vector<VarDecl> ParseContext::ShaderParams(std::vector<VarDecl> params) {
    RequireSizes(params);
    return params;
}

void ParseContext::AddShader(ShaderKind kind, SourceLoc loc, std::string name, std::vector<VarDecl> params,
                             StmtList body) {
    ShaderDef def;
    def.kind = kind;
    def.name = std::move(name);
    def.loc = loc;
    def.params = std::move(params);
    def.body = std::move(body.items);
    m_unit.shaders.push_back(std::move(def));
}

namespace {

// The names of the functions `e` and `s` call, into *out. Trees are within the nesting limit.
void CollectCalls(const Expr& e, std::set<std::string>* out) {
    if (e.kind == ExprKind::Call) out->insert(e.name);
    for (const ExprPtr& a : e.args)
        if (a) CollectCalls(*a, out);
}

void CollectCalls(const Stmt& s, std::set<std::string>* out) {
    for (const Expr* e : {s.expr.get(), s.init.get(), s.step.get()})
        if (e) CollectCalls(*e, out);
    for (const VarDecl& v : s.decls) {
        if (v.init) CollectCalls(*v.init, out);
        for (const ExprPtr& e : v.initList)
            if (e) CollectCalls(*e, out);
    }
    for (const StmtPtr& b : s.body)
        if (b) CollectCalls(*b, out);
    if (s.function)
        for (const StmtPtr& b : s.function->body)
            if (b) CollectCalls(*b, out);
}

}  // namespace

// A shader class becomes the displacement shader of the same name and parameters whose body
// declares the members, defines the methods its run needs (as nested functions, which see the
// members), and calls `construct()` and `begin()` if the class has them, then `displacement()`.
// The displacement method's parameters are the globals it changes, `output point P; output
// normal N`; in the body P and N are those globals. Methods no run reaches (`surface`,
// `lighting`, `opacity` and their helpers) are left out unchecked, as another renderer's
// displacement pass leaves them out; the entry methods are renamed `class::method`, names no
// source can call, so that they cannot clash with the message-passing `displacement()`.
void ParseContext::AddClass(SourceLoc loc, std::string name, std::vector<VarDecl> params, StmtList items) {
    std::map<std::string, Stmt*> methods;
    for (StmtPtr& item : items.items) {
        if (item->kind != StmtKind::FunctionDef) continue;
        const std::string& method = item->function->name;
        if (!methods.emplace(method, item.get()).second)
            Error(item->function->loc, "redefinition of method '" + method + "' of class '" + name + "'");
    }
    if (!methods.count("displacement")) {
        Error(loc, "class '" + name +
                       "' has no displacement method: affray runs a shader class by its `public void "
                       "displacement(output point P; output normal N)`");
        return;
    }
    const char* entries[] = {"construct", "begin", "displacement"};
    for (const char* entry : entries) {
        auto m = methods.find(entry);
        if (m == methods.end()) continue;
        for (const VarDecl& v : m->second->function->params) {
            const bool global = m->first == "displacement" && (v.name == "P" || v.name == "N");
            if (!global)
                Error(v.loc, m->first == "displacement"
                                 ? "parameter '" + v.name +
                                       "' of a displacement method: its parameters are the globals it changes, "
                                       "`output point P; output normal N`"
                                 : "method '" + m->first + "' of a shader class takes no parameters");
        }
        m->second->function->params.clear();
    }

    // The methods a run reaches, from the entries through the calls of each.
    std::set<std::string> reached, calls;
    std::vector<const Stmt*> pending;
    for (const char* entry : entries)
        if (auto m = methods.find(entry); m != methods.end()) {
            reached.insert(entry);
            pending.push_back(m->second);
        }
    for (const StmtPtr& item : items.items)
        if (item->kind == StmtKind::Decl) pending.push_back(item.get());
    while (!pending.empty()) {
        const Stmt* s = pending.back();
        pending.pop_back();
        calls.clear();
        CollectCalls(*s, &calls);
        for (const std::string& callee : calls)
            if (auto m = methods.find(callee); m != methods.end() && reached.insert(callee).second)
                pending.push_back(m->second);
    }

    StmtList body;
    for (StmtPtr& item : items.items) {
        if (item->kind == StmtKind::FunctionDef) {
            if (!reached.count(item->function->name)) continue;
            for (const char* entry : entries)
                if (item->function->name == entry) item->function->name = "class::" + std::string(entry);
        }
        body.items.push_back(std::move(item));
    }
    body.depth = items.depth;
    for (const char* entry : entries)
        if (methods.count(entry))
            Append(body, Simple(StmtKind::Expr, loc, Call(loc, "class::" + std::string(entry), {})));
    AddShader(ShaderKind::Displacement, loc, std::move(name), std::move(params), std::move(body));
}

std::shared_ptr<FunctionDef> ParseContext::FunctionHead(TypeName type, SourceLoc loc, std::string name,
                                                        std::vector<VarDecl> params) {
    auto def = std::make_shared<FunctionDef>();
    def->returnType = type;
    def->name = std::move(name);
    def->loc = loc;
    for (VarDecl& v : params) {
        if (v.init || v.hasInitList) {
            Error(v.loc, "parameter '" + v.name + "' of function '" + def->name + "' cannot have a default value");
            v.init = nullptr;
            v.hasInitList = false;
            v.initList.clear();
        }
    }
    def->params = std::move(params);
    return def;
}

FunctionNode ParseContext::FunctionBody(std::shared_ptr<FunctionDef> head, StmtList body) {
    head->body = std::move(body.items);
    return {std::move(head), body.depth};
}

void ParseContext::AddFunction(FunctionNode f) { m_unit.functions.push_back(std::move(f.def)); }

StmtNode ParseContext::Function(SourceLoc loc, FunctionNode f) {
    auto s = std::make_unique<Stmt>(StmtKind::FunctionDef, loc);
    s->function = std::move(f.def);
    return Finish(std::move(s), 1 + f.depth);
}

// --- Entry point -------------------------------------------------------------------------------

namespace {

// Parses `text` as the contents of diags.file(); with `markerFiles`, line markers switch files.
TranslationUnit ParseText(Diagnostics& diags, const std::string& text, bool markerFiles) {
    int errorsBefore = diags.errorCount();
    if (text.size() > MaxSourceBytes()) {
        diags.error({}, "file too large to parse (more than " + std::to_string(MaxSourceBytes()) + " bytes) " +
                            diag::LimitNote(diag::Limit::SourceBytes));
        return {};
    }

    ParseContext ctx(diags, markerFiles);
    try {
        std::unique_ptr<void, void (*)(void*)> scanner(NewScanner(ctx, text), DeleteScanner);
        Parser parser(ctx);
        // Every way to fail reports first; this is a net under that rule, not a message users see.
        if (parser.parse() != 0 && diags.errorCount() == errorsBefore) diags.error(ctx.lex().lastEnd, "syntax error");
    } catch (const std::bad_alloc&) {
        diags.error(ctx.lex().Here(), "out of memory while parsing");
    } catch (const std::exception& e) {
        diags.error(ctx.lex().Here(), std::string("internal error while parsing: ") + e.what());
    }

    if (diags.errorCount() == errorsBefore && ctx.unit().shaders.empty())
        diags.error({1, 1}, "no shader definition in file");
    return std::move(ctx.unit());
}

}  // namespace

TranslationUnit Parse(Diagnostics& diags) { return ParseText(diags, diags.file().text(), false); }

TranslationUnit PreprocessAndParse(Diagnostics& diags, const PreprocessOptions& options) {
    PreprocessResult pre = Preprocess(diags.file().path(), diags.file().text(), options);
    for (const std::string& path : pre.files) diags.fileIndex(path);
    for (diag::Diagnostic& d : pre.errors) diags.add(std::move(d));
    if (!pre.ok) return {};
    return ParseText(diags, pre.text, true);
}

}  // namespace affray::lang
