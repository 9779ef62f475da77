// lang/parser.y: the RSL grammar (Bison 3.8, C++ skeleton, pure, IELR(1), no conflicts).
// Owns the token kinds and their readable names, operator precedence and the shape of every
// construct. Actions only build AST nodes through ParseContext (parse.cpp); the few rules a
// context-free grammar cannot say well (assignment targets, tuple sizes, nesting depth) are
// checked there, as are array sizes, initialiser lists and what each kind of declaration may
// have (defaults, unsized arrays). The grammar has no conflicts (%expect 0); keep it that way.
// To add a construct: add its tokens here and in lexer.l, a rule whose action calls a builder,
// and a case in ast.cpp's ToString.
//
// Token names in messages: "identifier", "number", "string", "end of file", keywords quoted
// ('float', 'if', ...), operators and punctuation quoted (';', '+=', '&&', ...). So a message reads
//     syntax error, unexpected identifier, expecting ';'
// Error recovery: a bad statement is skipped up to its ';' (or the '}' closing its block); a bad
// initialiser list up to its '}'; a bad parameter list up to the '{' of the shader's or the
// function's body; garbage between definitions token by token until the next shader keyword or
// type (which starts a function). After a '}' or a shader's or function's body has resynchronised
// the parser (yyerrok) the next error is reported at once; elsewhere bison's usual rule holds
// (three tokens must be shifted before another error is reported), which keeps a statement
// recovered at the wrong ';' from reporting its block's '}' as a second error.

%require "3.8"
%skeleton "lalr1.cc"
%define api.namespace {affray::lang}
%define api.parser.class {Parser}
%define api.value.type variant
%define api.value.automove
%define api.token.constructor
%define api.token.prefix {TOK_}
%define api.location.type {affray::lang::SourceLoc}
%define parse.error detailed
// No LAC: with default reductions done first, the expected-token list is short and to the point
// ("expecting ';'" rather than every operator that could also follow). IELR keeps LALR's state
// merging from inventing expectations.
%define lr.type ielr
%define parse.assert
%locations
%param {ParseContext& ctx}
%expect 0

%code requires {
#include <string>
#include <utility>
#include <vector>

#include "diag/limits.h"
#include "lang/ast.h"
#include "lang/diagnostics.h"

namespace affray::lang {

/// Where the lexer is in the text; the lexer (lexer.l) updates it for every token it matches.
struct LexState {
    void* scanner = nullptr;  // the flex scanner (yyscan_t)
    int line = 1;             // where the next token starts
    int column = 1;
    int file = 0;             // Diagnostics::fileIndex of the file being read (line markers set it)
    SourceLoc token;          // where the current token starts
    SourceLoc commentStart;   // of the open /* comment
    int nesting = 0;          // parentheses, brackets and braces open now
    SourceLoc lastEnd{1, 1};  // just after the last token returned
    bool tokenHadError = false;  // the lexer reported an error while reading the last token

    /// Records the start of a token of `length` bytes at the current position and moves past it.
    void Advance(const char* text, int length);
    SourceLoc Here() const { return {line, column, file}; }
};

/// A tree under construction, with its depth (1 for a leaf; 0 for none), so that the builders
/// can enforce the nesting limit (ParseContext::maxNesting) in constant time per node.
struct ExprNode {
    ExprPtr expr;
    int depth = 0;
};
struct ExprList {
    std::vector<ExprPtr> items;
    int depth = 0;  // of the deepest item
};
struct StmtNode {
    StmtPtr stmt;
    int depth = 0;
};
struct StmtList {
    std::vector<StmtPtr> items;
    int depth = 0;
};
/// A function definition with the depth of its body.
struct FunctionNode {
    std::shared_ptr<FunctionDef> def;
    int depth = 0;
};
/// What follows a declared name's '=': an expression, or a list in braces (isList).
struct Init {
    SourceLoc loc;      // of its first token
    ExprNode expr;
    ExprList list;
    bool isList = false;
    bool bad = false;   // a list with a syntax error in it, already reported
};

/// The state of one Parse() call, shared by the lexer and the parser's actions: the diagnostics,
/// the unit being built, and the node builders that enforce the nesting limits.
class ParseContext {
  public:
    /// The nesting limit (diag/limits.h), read once per parse. It bounds both the open
    /// parentheses, brackets and braces at once (past it, parsing stops with an error) and the
    /// depth of an expression or statement tree (operators chain without parentheses, as in
    /// `- - - x` or `if (a) if (b) ...`; past it, the subtree is replaced and parsing goes on), so
    /// that every later recursive pass has a bounded depth.
    int maxNesting() const { return m_maxNesting; }

    /// With `markerFiles`, a line marker's file name also changes the file of later locations
    /// (preprocessed text); without it, only the line changes and every location is in the main
    /// file (text written by hand).
    explicit ParseContext(Diagnostics& diags, bool markerFiles = false)
        : m_diags(diags), m_markerFiles(markerFiles) {}

    /// Reports an error unless parsing has stopped. Past Diagnostics::kMaxErrors, stops.
    void Error(SourceLoc loc, std::string message);
    /// Ends the parse early: the lexer returns end of file and later syntax errors go unsaid.
    void Stop() { m_stopped = true; }
    bool StoppedP() const { return m_stopped; }
    int ErrorCount() const { return m_diags.errorCount(); }
    bool MarkerFilesP() const { return m_markerFiles; }
    /// Diagnostics::fileIndex of `path`, for a line marker naming it.
    int FileIndex(const std::string& path) { return m_diags.fileIndex(path); }
    LexState& lex() { return m_lex; }
    TranslationUnit& unit() { return m_unit; }

    // Node builders (parse.cpp). Each takes ownership of its operands and returns a non-null
    // node, so a tree built while recovering from errors is still safe to walk.
    ExprNode Number(SourceLoc loc, double value);
    ExprNode String(SourceLoc loc, std::string text);
    ExprNode Ident(SourceLoc loc, std::string name);
    ExprNode Unary(UnaryOp op, SourceLoc loc, ExprNode operand);
    ExprNode Binary(BinaryOp op, SourceLoc loc, ExprNode lhs, ExprNode rhs);
    /// `target op value`; reports an error at the operator unless target is a plain name.
    ExprNode Assign(AssignOp op, SourceLoc loc, ExprNode target, ExprNode value);
    ExprNode Call(SourceLoc loc, std::string name, ExprList args);
    /// `(first, rest...)`: a triple or a 16-tuple (a matrix); other sizes are an error at '('.
    ExprNode Tuple(SourceLoc loc, ExprNode first, ExprList rest);
    /// `array[index]`, at the '['.
    ExprNode Index(SourceLoc loc, ExprNode array, ExprNode index);
    ExprNode Cast(SourceLoc loc, TypeName type, std::string space, ExprNode operand);
    ExprNode Ternary(SourceLoc loc, ExprNode cond, ExprNode yes, ExprNode no);
    void Append(ExprList& list, ExprNode e);

    StmtNode Simple(StmtKind kind, SourceLoc loc, ExprNode expr = {});
    StmtNode Decl(SourceLoc loc, std::vector<VarDecl> decls);
    StmtNode Block(SourceLoc loc, StmtList body);
    StmtNode If(SourceLoc loc, ExprNode cond, StmtNode yes, StmtNode no);
    StmtNode For(SourceLoc loc, ExprNode init, ExprNode cond, ExprNode step, StmtNode body);
    StmtNode While(SourceLoc loc, ExprNode cond, StmtNode body);
    StmtNode Jump(StmtKind kind, SourceLoc loc, int level);
    void Append(StmtList& list, StmtNode s);
    /// The N of `break N`: reports an error unless it is a positive integer.
    int JumpLevel(SourceLoc loc, double value);

    /// Appends `name [[N]] [= init]` to a declaration list still waiting for its type; reports
    /// an init list on a non-array, an array initialised without braces, and a list whose length
    /// is not the array's size.
    /// `arraySize` is VarDecl::arraySize.
    void AddVar(std::vector<VarDecl>& list, SourceLoc loc, std::string name, int arraySize,
                Init init);
    /// The N of `[N]`: reports an error unless it is a positive integer.
    int ArraySize(SourceLoc loc, double value);
    /// `=` followed by an expression or by a list in braces, for AddVar.
    Init ExprInit(SourceLoc loc, ExprNode expr);
    Init ListInit(SourceLoc loc, ExprList list, bool bad = false);
    /// Gives every variable in `list` the shared type, detail and output flag.
    std::vector<VarDecl> Typed(std::vector<VarDecl> list, TypeName type, Detail detail,
                               bool output);
    /// `extern type a, b`: marks the variables extern; reports any initialiser.
    std::vector<VarDecl> Extern(std::vector<VarDecl> list);
    /// Reports unsized arrays among a shader's parameters.
    std::vector<VarDecl> ShaderParams(std::vector<VarDecl> params);
    void AddShader(ShaderKind kind, SourceLoc loc, std::string name, std::vector<VarDecl> params,
                   StmtList body);
    /// A shader class: its members (declarations) and methods (function definitions) in `items`.
    /// Added as the displacement shader its `displacement` method runs (parse.cpp).
    void AddClass(SourceLoc loc, std::string name, std::vector<VarDecl> params, StmtList items);
    /// `type name(params)`, the head of a function definition: reports parameters with defaults.
    std::shared_ptr<FunctionDef> FunctionHead(TypeName type, SourceLoc loc, std::string name,
                                              std::vector<VarDecl> params);
    /// The definition with its body; then added at the top level, or nested as a statement.
    FunctionNode FunctionBody(std::shared_ptr<FunctionDef> head, StmtList body);
    void AddFunction(FunctionNode f);
    StmtNode Function(SourceLoc loc, FunctionNode f);

  private:
    ExprNode Finish(ExprPtr e, int depth);
    /// Reports unsized arrays among `decls` unless each is allowed to be one.
    void RequireSizes(const std::vector<VarDecl>& decls);
    StmtNode Finish(StmtPtr s, int depth);

    Diagnostics& m_diags;
    bool m_markerFiles = false;
    LexState m_lex;
    TranslationUnit m_unit;
    bool m_stopped = false;
    int m_maxNesting = static_cast<int>(diag::LimitValue(diag::Limit::Nesting));
    bool m_reportedExprDepth = false;
    bool m_reportedStmtDepth = false;
};

}  // namespace affray::lang
}

%code provides {
namespace affray::lang {
// The scanner over one text (lexer.l): created before parsing, destroyed after.
void* NewScanner(ParseContext& ctx, const std::string& text);
void DeleteScanner(void* scanner);
// The next token; end of file for ever once ctx.StoppedP().
Parser::symbol_type yylex(ParseContext& ctx);
}  // namespace affray::lang
}

%code {
// A nonterminal's location is where its first token starts (an empty one takes the previous
// symbol's), so an action's @1 is the first token of its first symbol.
#define YYLLOC_DEFAULT(Current, Rhs, N) \
    do { (Current) = (N) ? YYRHSLOC(Rhs, 1) : YYRHSLOC(Rhs, 0); } while (false)
}

%token END 0 "end of file"
%token <std::string> IDENT "identifier"
%token <double> NUMBER "number"
%token <std::string> STRING "string"
%token FLOAT "'float'" POINT "'point'" VECTOR "'vector'" NORMAL "'normal'" COLOR "'color'"
%token STRING_TYPE "'string'" VOID "'void'" MATRIX "'matrix'"
%token UNIFORM "'uniform'" VARYING "'varying'" OUTPUT "'output'" EXTERN "'extern'"
%token IF "'if'" ELSE "'else'" FOR "'for'" WHILE "'while'" RETURN "'return'"
%token BREAK "'break'" CONTINUE "'continue'"
%token DISPLACEMENT "'displacement'" SURFACE "'surface'" LIGHT "'light'" VOLUME "'volume'"
%token IMAGER "'imager'" CLASS "'class'" PUBLIC "'public'"
%token ILLUMINANCE "'illuminance'" ILLUMINATE "'illuminate'" SOLAR "'solar'"
%token ADD_ASSIGN "'+='" SUB_ASSIGN "'-='" MUL_ASSIGN "'*='" DIV_ASSIGN "'/='"
%token OR "'||'" AND "'&&'" EQ "'=='" NE "'!='" LE "'<='" GE "'>='"

// Lowest first. Assignment and ?: are right-recursive rules below, not precedences.
%precedence THEN
%precedence ELSE
// `point "space" -x`: after a type and a string, '+'/'-' start the cast's operand (shift).
%precedence SPACE_STRING
%left OR
%left AND
%left '<' '>' LE GE EQ NE
%left '+' '-'
%left '^'
%left '*' '/'
%left '.'

%nterm <ShaderKind> shader_kind
%nterm <std::vector<VarDecl>> shader_params params param_groups param_group var_items decl
%nterm <ExprNode> expr expr_nc cond cond_nc binary binary_nc unary unary_nc primary
%nterm <ExprNode> opt_expr
%nterm <ExprList> args arg_list
%nterm <Init> opt_init
%nterm <std::shared_ptr<FunctionDef>> function_head
%nterm <FunctionNode> function
%nterm <StmtList> stmts body class_items
%nterm <StmtNode> class_item
%nterm <std::string> method_name
%nterm <StmtNode> stmt
%nterm <TypeName> type
%nterm <Detail> detail opt_detail
%nterm <bool> opt_output
%nterm <AssignOp> assign_op
%nterm <BinaryOp> rel_op add_op mul_op
%nterm <int> opt_level opt_array

%start unit

%%

unit
  : %empty
  | unit shader
  | unit function  { ctx.AddFunction($2); }
  | unit shader_class
  | unit error  // skips one token at a time until a shader keyword or a type
  ;

shader
  : shader_kind IDENT '(' shader_params ')' body
      { ctx.AddShader($1, @2, $2, $4, $6); }
  | shader_kind IDENT '(' error body
      { ctx.AddShader($1, @2, $2, {}, $5); yyerrok; }
  ;

shader_kind
  : DISPLACEMENT  { $$ = ShaderKind::Displacement; }
  | SURFACE       { $$ = ShaderKind::Surface; }
  | LIGHT         { $$ = ShaderKind::Light; }
  | VOLUME        { $$ = ShaderKind::Volume; }
  | IMAGER        { $$ = ShaderKind::Imager; }
  ;

// Checked as soon as they are read, so that their errors come before the body's.
shader_params
  : params  { $$ = ctx.ShaderParams($1); }
  ;

// A function definition, `type name(params) { body }`, at the top level or as a statement. Its
// parameters are written like a shader's; FunctionHead rejects their defaults.
function
  : function_head body         { $$ = ctx.FunctionBody($1, $2); }
  | type IDENT '(' error body  { $$ = ctx.FunctionBody(ctx.FunctionHead($1, @2, $2, {}), $5);
                                 yyerrok; }
  ;

function_head
  : type IDENT '(' params ')'  { $$ = ctx.FunctionHead($1, @2, $2, $4); }
  ;

// Shader and function parameters: `[output] [uniform|varying] type a = 1, b[2] = {1, 2}; type
// c = 3;` with an optional ';' before the ')'.
params
  : %empty             { }
  | param_groups       { $$ = $1; }
  | param_groups ';'   { $$ = $1; }
  ;

param_groups
  : param_group                    { $$ = $1; }
  | param_groups ';' param_group
      { $$ = $1; for (VarDecl& v : $3) $$.push_back(std::move(v)); }
  ;

param_group
  : opt_output opt_detail type var_items  { $$ = ctx.Typed($4, $3, $2, $1); }
  ;

opt_output
  : %empty  { $$ = false; }
  | OUTPUT  { $$ = true; }
  ;

opt_detail
  : %empty  { $$ = Detail::Default; }
  | detail  { $$ = $1; }
  ;

detail
  : UNIFORM  { $$ = Detail::Uniform; }
  | VARYING  { $$ = Detail::Varying; }
  ;

// Names that will share one type: `a = 1, b, c[3] = {1, 2, 3}, d[]`.
var_items
  : IDENT opt_array opt_init                { ctx.AddVar($$, @1, $1, $2, $3); }
  | var_items ',' IDENT opt_array opt_init  { $$ = $1; ctx.AddVar($$, @3, $3, $4, $5); }
  ;

opt_array
  : %empty          { $$ = -1; }
  | '[' NUMBER ']'  { $$ = ctx.ArraySize(@2, $2); }
  | '[' ']'         { $$ = 0; }
  ;

opt_init
  : %empty                { }
  | '=' expr              { $$ = ctx.ExprInit(@2, $2); }
  | '=' '{' arg_list '}'  { $$ = ctx.ListInit(@2, $3); }
  | '=' '{' error '}'     { $$ = ctx.ListInit(@2, {}, true); }
  ;

// `void` is accepted wherever a type is; the compiler rejects void variables.
type
  : FLOAT        { $$ = TypeName::Float; }
  | POINT        { $$ = TypeName::Point; }
  | VECTOR       { $$ = TypeName::Vector; }
  | NORMAL       { $$ = TypeName::Normal; }
  | COLOR        { $$ = TypeName::Color; }
  | STRING_TYPE  { $$ = TypeName::String; }
  | VOID         { $$ = TypeName::Void; }
  | MATRIX       { $$ = TypeName::Matrix; }
  ;

body
  : '{' stmts '}'        { $$ = $2; }
  | '{' stmts error '}'  { $$ = $2; yyerrok; }
  ;

stmts
  : %empty      { }
  | stmts stmt  { $$ = $1; ctx.Append($$, $2); }
  ;

stmt
  : ';'                     { $$ = ctx.Simple(StmtKind::Empty, @1); }
  | expr_nc ';'             { $$ = ctx.Simple(StmtKind::Expr, @1, $1); }
  | decl ';'                { $$ = ctx.Decl(@1, $1); }
  | body                    { $$ = ctx.Block(@1, $1); }
  | IF '(' expr ')' stmt %prec THEN
      { $$ = ctx.If(@1, $3, $5, {}); }
  | IF '(' expr ')' stmt ELSE stmt
      { $$ = ctx.If(@1, $3, $5, $7); }
  | WHILE '(' expr ')' stmt
      { $$ = ctx.While(@1, $3, $5); }
  // The light loops of surface and light shaders, `illuminance (P, N, angle) stmt` and the
  // like, are an `if` on a call of the same name: the compiler type-checks the call and reports
  // it only where a displacement shader runs it (compiler/lower_surface.cpp).
  | ILLUMINANCE '(' args ')' stmt  { $$ = ctx.If(@1, ctx.Call(@1, "illuminance", $3), $5, {}); }
  | ILLUMINATE '(' args ')' stmt   { $$ = ctx.If(@1, ctx.Call(@1, "illuminate", $3), $5, {}); }
  | SOLAR '(' args ')' stmt        { $$ = ctx.If(@1, ctx.Call(@1, "solar", $3), $5, {}); }
  | FOR '(' opt_expr ';' opt_expr ';' opt_expr ')' stmt
      { $$ = ctx.For(@1, $3, $5, $7, $9); }
  | RETURN opt_expr ';'     { $$ = ctx.Simple(StmtKind::Return, @1, $2); }
  | BREAK opt_level ';'     { $$ = ctx.Jump(StmtKind::Break, @1, $2); }
  | CONTINUE opt_level ';'  { $$ = ctx.Jump(StmtKind::Continue, @1, $2); }
  | function                { $$ = ctx.Function(@1, $1); }
  | error ';'               { $$ = ctx.Simple(StmtKind::Empty, @1); }
  ;

// A local declaration. A statement that starts with a type is always a declaration (or a
// function definition), so an expression statement cannot start with a cast (see expr_nc).
decl
  : type var_items                { $$ = ctx.Typed($2, $1, Detail::Default, false); }
  | detail type var_items         { $$ = ctx.Typed($3, $2, $1, false); }
  | EXTERN type var_items         { $$ = ctx.Extern(ctx.Typed($3, $2, Detail::Default, false)); }
  | EXTERN detail type var_items  { $$ = ctx.Extern(ctx.Typed($4, $3, $2, false)); }
  ;

opt_level
  : %empty  { $$ = 1; }
  | NUMBER  { $$ = ctx.JumpLevel(@1, $1); }
  ;

opt_expr
  : %empty  { }
  | expr    { $$ = $1; }
  ;

// Expressions, lowest precedence first. Each *_nc rule is its twin that does not start with a
// cast; only expression statements use them. Relational operators share one level and are
// left-associative (`a < b == c` is `(a < b) == c`); the compiler decides what types they take.
expr
  : cond                    { $$ = $1; }
  | cond assign_op expr     { $$ = ctx.Assign($2, @2, $1, $3); }
  ;

expr_nc
  : cond_nc                 { $$ = $1; }
  | cond_nc assign_op expr  { $$ = ctx.Assign($2, @2, $1, $3); }
  ;

assign_op
  : '='         { $$ = AssignOp::Assign; }
  | ADD_ASSIGN  { $$ = AssignOp::AddAssign; }
  | SUB_ASSIGN  { $$ = AssignOp::SubAssign; }
  | MUL_ASSIGN  { $$ = AssignOp::MulAssign; }
  | DIV_ASSIGN  { $$ = AssignOp::DivAssign; }
  ;

cond
  : binary                    { $$ = $1; }
  | binary '?' expr ':' cond  { $$ = ctx.Ternary(@2, $1, $3, $5); }
  ;

cond_nc
  : binary_nc                    { $$ = $1; }
  | binary_nc '?' expr ':' cond  { $$ = ctx.Ternary(@2, $1, $3, $5); }
  ;

binary
  : unary                         { $$ = $1; }
  | binary OR binary              { $$ = ctx.Binary(BinaryOp::Or, @2, $1, $3); }
  | binary AND binary             { $$ = ctx.Binary(BinaryOp::And, @2, $1, $3); }
  | binary rel_op binary %prec EQ { $$ = ctx.Binary($2, @2, $1, $3); }
  | binary add_op binary %prec '+' { $$ = ctx.Binary($2, @2, $1, $3); }
  | binary '^' binary             { $$ = ctx.Binary(BinaryOp::Cross, @2, $1, $3); }
  | binary mul_op binary %prec '*' { $$ = ctx.Binary($2, @2, $1, $3); }
  | binary '.' binary             { $$ = ctx.Binary(BinaryOp::Dot, @2, $1, $3); }
  ;

binary_nc
  : unary_nc                         { $$ = $1; }
  | binary_nc OR binary              { $$ = ctx.Binary(BinaryOp::Or, @2, $1, $3); }
  | binary_nc AND binary             { $$ = ctx.Binary(BinaryOp::And, @2, $1, $3); }
  | binary_nc rel_op binary %prec EQ { $$ = ctx.Binary($2, @2, $1, $3); }
  | binary_nc add_op binary %prec '+' { $$ = ctx.Binary($2, @2, $1, $3); }
  | binary_nc '^' binary             { $$ = ctx.Binary(BinaryOp::Cross, @2, $1, $3); }
  | binary_nc mul_op binary %prec '*' { $$ = ctx.Binary($2, @2, $1, $3); }
  | binary_nc '.' binary             { $$ = ctx.Binary(BinaryOp::Dot, @2, $1, $3); }
  ;

rel_op
  : '<'  { $$ = BinaryOp::Less; }
  | LE   { $$ = BinaryOp::LessEq; }
  | '>'  { $$ = BinaryOp::Greater; }
  | GE   { $$ = BinaryOp::GreaterEq; }
  | EQ   { $$ = BinaryOp::Equal; }
  | NE   { $$ = BinaryOp::NotEqual; }
  ;

add_op
  : '+'  { $$ = BinaryOp::Add; }
  | '-'  { $$ = BinaryOp::Sub; }
  ;

mul_op
  : '*'  { $$ = BinaryOp::Mul; }
  | '/'  { $$ = BinaryOp::Div; }
  ;

// Unary operators bind tighter than every binary one: `-a . b` is `(-a) . b`. A cast is
// `type ["space"] operand` with a unary-level operand: `float noise(P)`, `point "world" (0,0,1)`.
unary
  : unary_nc                { $$ = $1; }
  | type unary              { $$ = ctx.Cast(@1, $1, "", $2); }
  | type STRING unary       { $$ = ctx.Cast(@1, $1, $2, $3); }
  ;

unary_nc
  : primary    { $$ = $1; }
  | '-' unary  { $$ = ctx.Unary(UnaryOp::Negate, @1, $2); }
  | '+' unary  { $$ = $2; }
  | '!' unary  { $$ = ctx.Unary(UnaryOp::Not, @1, $2); }
  ;

primary
  : NUMBER                          { $$ = ctx.Number(@1, $1); }
  | STRING %prec SPACE_STRING       { $$ = ctx.String(@1, $1); }
  | IDENT                           { $$ = ctx.Ident(@1, $1); }
  | IDENT '(' args ')'              { $$ = ctx.Call(@1, $1, $3); }
  // The message-passing functions surface("Kd", kd) and displacement("Km", km) share their
  // names with shader kinds; in an expression they are calls (compiler/lower_surface.cpp).
  | SURFACE '(' args ')'            { $$ = ctx.Call(@1, "surface", $3); }
  | DISPLACEMENT '(' args ')'       { $$ = ctx.Call(@1, "displacement", $3); }
  | primary '[' expr ']'            { $$ = ctx.Index(@2, $1, $3); }
  | '(' expr ')'                    { $$ = $2; }
  | '(' expr ',' arg_list ')'       { $$ = ctx.Tuple(@1, $2, $4); }
  ;

args
  : %empty    { }
  | arg_list  { $$ = $1; }
  ;

arg_list
  : expr               { ctx.Append($$, $1); }
  | arg_list ',' expr  { $$ = $1; ctx.Append($$, $3); }
  ;

// (Last in the grammar, so that the numbers Bison gives the character tokens, which order the
// "expecting ..." lists of syntax errors, stay as they were before classes.)
// A shader class (RenderMan Shading Language 2): `class name(params) { members and methods }`,
// methods written as functions, optionally `public`. AddClass makes it a displacement shader run
// by its `displacement` method (parse.cpp says how).
shader_class
  : CLASS IDENT '(' shader_params ')' '{' class_items '}'
      { ctx.AddClass(@2, $2, $4, std::move($7)); }
  | CLASS IDENT '(' error '{' class_items '}'
      { ctx.AddClass(@2, $2, {}, std::move($6)); yyerrok; }
  ;

class_items
  : %empty                  { }
  | class_items class_item  { $$ = $1; ctx.Append($$, $2); }
  ;

// The pipeline methods are named by keywords (`displacement`, `surface`, ...).
class_item
  : opt_public type method_name '(' params ')' body
      { $$ = ctx.Function(@2, ctx.FunctionBody(ctx.FunctionHead($2, @3, $3, $5), $7)); }
  | opt_public decl ';'  { $$ = ctx.Decl(@2, $2); }
  | error ';'            { $$ = ctx.Simple(StmtKind::Empty, @1); }
  | error body           { $$ = ctx.Simple(StmtKind::Empty, @1); }
  ;

opt_public
  : %empty
  | PUBLIC
  ;

method_name
  : IDENT         { $$ = $1; }
  | DISPLACEMENT  { $$ = "displacement"; }
  | SURFACE       { $$ = "surface"; }
  | LIGHT         { $$ = "light"; }
  | VOLUME        { $$ = "volume"; }
  | IMAGER        { $$ = "imager"; }
  ;

%%

namespace affray::lang {

// A syntax error at a token the lexer already complained about (say, after skipping an invalid
// character) is the same mistake said twice: keep the lexer's, more precise, message.
void Parser::error(const location_type& loc, const std::string& message) {
    if (!ctx.lex().tokenHadError) ctx.Error(loc, message);
}

}  // namespace affray::lang
