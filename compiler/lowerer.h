// compiler/lowerer.h: the lowering walk's state, shared by its files (private to compiler/).
// lower.cpp owns names, declarations and expressions (lower_logic.cpp the comparisons and
// conditions), lower_flow.cpp statements and control flow, lower_functions.cpp user functions
// and arrays, lower_library.cpp the built-ins that need the lowerer.
// The walk keeps variables as IR values, so control flow becomes data flow:
//  - `alive` is a boolean IR value: "execution reaches this point" on the current path. An
//    assignment under an alive that is not the constant 1 selects between the new and the old
//    value, so paths that already left (break, continue, return) keep their values.
//  - if/else lowers both arms from the same state and merges the two states with Select on the
//    condition (one Select per variable an arm changed). A constant condition folds the Select
//    away, so only the arm taken remains.
//  - Loops are unrolled: each iteration runs while `alive && condition` may hold; a constant
//    condition ends the unrolling exactly, a varying one after varying-loop-iterations (diag/limits.h),
//    past which the paths still running get NaN (Unbounded in bound types), never a wrong value.
// Sources: Allen, Kennedy, Porterfield & Warren, "Conversion of control dependence to data
// dependence" (POPL 1983), i.e. if-conversion; OSL's runtime optimiser for the folding.
#pragma once

#include <functional>
#include <map>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "compiler/lower.h"
#include "compiler/typecheck.h"
#include "diag/limits.h"

namespace affray::compiler {

struct Variable {
    Type type = Type::Float;
    Value value;
    bool assigned = false;
    bool writable = true;
    bool isGlobal = false;
    bool used = false;
    lang::SourceLoc loc;
    /// Arrays: the size (else -1) and the elements, each of `type`; `value` is unused.
    int arraySize = -1;
    std::vector<Value> elements;
};

/// A loop or a function body being lowered: which paths left it, for break/continue/return.
struct FlowContext {
    bool isLoop = true;
    bool isShader = false;  // the shader body (a function that returns nothing)
    /// Paths that left for good (break, return; a multi-level break or continue passing through).
    ValueId left = kNoValue;
    /// Paths that skip the rest of this iteration (continue).
    ValueId skipped = kNoValue;
    /// Functions: the value returned on each path so far, and its type.
    Value returned;
    Type returnType = Type::Void;
};

/// Everything control flow must save and merge.
struct FlowState {
    std::vector<std::unordered_map<std::string, Variable>> scopes;
    ValueId alive = kNoValue;
    std::vector<FlowContext> contexts;
};

/// A spline basis: its matrix and how many knots a segment advances (lower_library.cpp).
struct SplineBasis {
    const char* name;
    double m[4][4];
    int step;
};
const SplineBasis* FindSplineBasis(const std::string& name);

class Lowerer {
  public:
    Lowerer(LoweredShader& out, lang::Diagnostics& diags, const std::vector<std::vector<double>>* paramValues,
            const std::map<std::string, std::string>* stringValues, const Spaces* spaces, const SceneFacts* facts);

    bool Run(const lang::ShaderDef& shader, const std::vector<std::shared_ptr<lang::FunctionDef>>& functions);

    /// Called with every expression LowerExpr lowers and the value it got (see LowerObserved).
    using Observer = std::function<void(const lang::Expr&, const Value&)>;
    void Observe(Observer observer) { m_observer = std::move(observer); }

  private:
    // --- expressions (lower.cpp; comparisons, conditions and ?: in lower_logic.cpp)
    std::optional<Value> LowerExpr(const lang::Expr& e);
    std::optional<Value> LowerExprOnce(const lang::Expr& e);  // LowerExpr before the observer
    Observer m_observer;
    std::optional<Value> LowerBinary(const lang::Expr& e);
    std::optional<Value> LowerComparison(const lang::Expr& e, const Value& a, const Value& b);
    std::optional<Value> LowerTernary(const lang::Expr& e);
    std::optional<Value> LowerAssign(const lang::Expr& e);
    std::optional<Value> LowerCast(const lang::Expr& e);
    std::optional<Value> LowerIdent(const lang::Expr& e);
    /// A call; `expected` is the type its context wants (only noise's result type depends on
    /// it; Void: none). The arguments are lowered with no expectation.
    std::optional<Value> LowerCall(const lang::Expr& e, Type expected);
    /// comp, setcomp and setxcomp/setycomp/setzcomp: component access by a constant index, the
    /// setters writing to their first argument, which must be a variable.
    std::optional<Value> LowerComponentCall(const lang::Expr& e);
    /// A condition: a boolean, or a float meaning "!= 0". Reports and returns nothing otherwise.
    std::optional<ValueId> LowerCondition(const lang::Expr& e);

    // --- user functions and arrays (lower_functions.cpp)
    /// The function `name` visible here (nested definitions shadow outer ones), or null.
    const lang::FunctionDef* FindFunction(const std::string& name) const;
    void DefineFunction(const lang::FunctionDef& f);
    /// Inlines a call of `f`: its body is lowered in place with the arguments bound to its
    /// parameters (output parameters written back), so recursion is a compile error.
    std::optional<Value> LowerUserCall(const lang::Expr& call, const lang::FunctionDef& f);
    std::optional<Value> LowerIndex(const lang::Expr& e);
    /// Element `index` of an array: a constant index is checked and picked, a varying one
    /// selects among the elements (NaN outside the array).
    std::optional<Value> Element(const Variable& array, const Value& index, lang::SourceLoc loc);
    void StoreElement(Variable& array, const Value& index, const Value& value);
    /// Declares an array variable from `d` (its initialiser list lowered here).
    void LowerArrayDecl(const lang::VarDecl& d);

    // --- built-ins that need the lowerer (lower_library.cpp)
    bool IsLibraryCall(const std::string& name) const;
    /// `expected`: the type the call's context wants (picks noise's result type), else Void.
    std::optional<Value> LowerLibraryCall(const lang::Expr& e, std::vector<Value> args, Type expected);
    /// A string naming a known, affine coordinate space; reports and returns nothing otherwise.
    std::optional<std::string> SpaceName(const Value& v, lang::SourceLoc loc);
    Value Spline(const SplineBasis& basis, const Value& t, const std::vector<Value>& knots);
    /// `x` (a point, vector or normal, as `kind` says) from `space` to current, and back.
    Value ToCurrent(const std::string& space, const Value& x, Type kind);
    Value FromCurrent(const std::string& space, const Value& x, Type kind);
    /// The matrix that maps current space to `space` (`matrix "space" 1`).
    Value CurrentTo(const std::string& space);
    /// Records that the shader names `space` (LoweredShader::spaces).
    void NoteSpace(const std::string& space);
    /// x mapped by the affine matrix m (a point: with its translation; a vector: without; a
    /// normal: by the transpose of `inverse`, m's inverse).
    Value MapBy(const Matrix4& m, const Matrix4& inverse, const Value& x, Type kind);
    /// Lowers `e` with `expected` as the type its context wants (picks noise's result type).
    std::optional<Value> LowerExpecting(const lang::Expr& e, Type expected);

    // --- the rest of the library (lower_extras.cpp): printf, format, concat, match, ctransform,
    // fresnel, refract, ptlined, random; each lowers its own arguments
    static bool IsExtraCall(const std::string& name);
    std::optional<Value> LowerExtraCall(const lang::Expr& e, Type expected);
    /// A string computed from values that vary: no constant text (StringOf gives nothing).
    Value VaryingString();
    int m_varyingStrings = 0;
    int m_randomCalls = 0;

    // --- surface and light shaders' functions and globals (lower_surface.cpp): checked, an
    // error only where the displacement shader runs them
    static bool IsSurfaceCall(const std::string& name);
    std::optional<Value> LowerSurfaceCall(const lang::Expr& e, Type expected);
    /// The type of a surface shader's global variable (Ci, Cs, L...), else Void.
    static Type SurfaceGlobalType(const std::string& name);
    /// Declares the surface globals in `scope` (while checking a function nobody calls).
    void AddSurfaceGlobals(std::unordered_map<std::string, Variable>& scope);
    /// option, attribute, rendererinfo, displacement (name, out): 1 and `out` written when the
    /// instance knows `name` with out's type, else 0 (folded; `nameArg` is the lowered name).
    std::optional<Value> LowerQuery(const lang::Expr& e, const Value& nameArg, Variable& out);
    /// texture(): lowered to texture slots and the Texture opcodes (lower_texture.cpp).
    std::optional<Value> LowerTexture(const lang::Expr& e, Type expected);
    /// The constant value of `v`, taking a parameter as its default (whose name is added to
    /// *params), or nothing if it varies over the surface.
    std::optional<double> OptionValue(ValueId v, std::vector<std::string>* params) const;
    /// The index of `slot` in LoweredShader::textures (added if new), or nothing if full.
    std::optional<int> TextureSlotIndex(const vm::TextureSlot& slot);
    /// The shader's parameter `name` as it is now, or null (also inside inlined functions).
    const Variable* ShaderParameter(const std::string& name) const;
    /// Whether a surface shader is being lowered (its globals, light loops and lighting
    /// functions are real; in a displacement shader they are only checked).
    bool IsSurface() const { return m_kind == lang::ShaderKind::Surface; }
    bool IsLight() const { return m_kind == lang::ShaderKind::Light; }
    /// A light shader's `illuminate (from [, axis, angle]) body` and `solar (axis, angle) body`
    /// (s: the `if` the parser made of it): L set (Ps - from, or the axis), the body run where L
    /// lies within the cone (always for solar: the cone is the lit surface's to test), and the
    /// shader's `lit` output set there.
    void LowerIlluminate(const lang::Stmt& s);
    /// The arguments of a light loop's call, each lowered (0 after an error, *ok then false).
    std::vector<Value> LowerLoopArguments(const lang::Expr& call, bool* ok);
    /// Where an illuminate or solar statement has run (a light shader's `lit`).
    ValueId m_lit = kNoValue;
    lang::ShaderKind m_kind = lang::ShaderKind::Displacement;
    /// `illuminance ([category,] P [, axis, angle]) body` (s: the `if` the parser made of it):
    /// the body once per light slot the category admits, with L and Cl that light's, under the
    /// condition that L lies within the cone (RI Spec 3.2 section 15.5.1).
    void LowerIlluminance(const lang::Stmt& s);
    /// A light slot's L (the vector from the shaded point to the light) and Cl (its colour
    /// there, shadowed where `shadowed` is not 0); slot vm::kAmbientSlot: the ambient lights.
    Value LightVector(int slot);
    Value LightColor(int slot, ValueId shadowed);
    /// Whether the unit vector Ln lies within `angle` of the unit vector `axisN` (the cone of a
    /// light loop; PI and more: every direction).
    ValueId InCone(const Value& Ln, const Value& axisN, const Value& angle);
    /// The light slots of the instance a loop of category `category` visits ("" all; "-name"
    /// those not in category name), in order; notes the read (SceneReads::lights).
    std::vector<int> LightSlots(const std::string& category);
    /// Whether `v` is a unit (or zero) vector by construction: a normalize's result (its pattern
    /// in the IR), its negation, or a select of such vectors by one condition (faceforward's).
    bool IsUnit(const Value& v) const;
    /// normalize(v), or v itself where IsUnit(v): normalising a normalised vector again changes
    /// it by an ulp at most, and costs 18 instructions.
    Value NormalizeOnce(const Value& v) { return IsUnit(v) ? v : m_ops.Normalize(v); }
    /// ambient(), diffuse(N), specular(N, V, roughness), specularbrdf(L, N, V, roughness) and
    /// phong(N, V, size) of a surface shader, from their RI Spec 3.2 definitions by illuminance.
    std::optional<Value> LowerLighting(const lang::Expr& e);

    // --- statements and control flow (lower_flow.cpp)
    void LowerStmt(const lang::Stmt& s);
    void LowerIf(const lang::Stmt& s);
    /// if (c) then else: the arms lowered and merged (`elseStmt` may be null); `c` a condition
    /// value already lowered.
    void LowerBranches(ValueId c, const lang::Stmt& thenStmt, const lang::Stmt* elseStmt);
    void LowerLoop(const lang::Stmt& s);
    void LowerJump(const lang::Stmt& s);
    /// Merges `thenState` (the state after the then arm) into the current state (after the else
    /// arm): cond ? then : else for every variable, alive and flow flag that differ.
    void Merge(ValueId cond, const FlowState& thenState);
    /// Writes `value` to `var` on the paths still alive.
    void Store(Variable& var, const Value& value);
    /// `value` where alive, `old` elsewhere.
    Value Guard(const Value& value, const Value& old);
    /// Reaches a Param node.
    bool DependsOnParameter(ValueId v) const;
    /// Marks in `into` the variables the current state has used (after lowering dead code).
    void KeepUsedFlags(FlowState& into) const;
    /// `v` simplified on the assumption that the current `alive` holds.
    ValueId AssumingAlive(ValueId v);
    /// alive with every path that left an enclosing context (from `firstContext` out) removed.
    ValueId AliveExcludingLeft(ValueId base, size_t firstContext);

    // --- declarations (lower.cpp)
    void LowerDecl(const lang::VarDecl& d, std::optional<Value> init);
    /// Declares `d` (as 0 of `type`, assigned and used) after an error in its declaration, so
    /// that its later uses do not repeat the error as "unknown identifier".
    void DeclarePlaceholder(const lang::VarDecl& d, Type type);
    /// Converts `v` for storing in a variable of `target` type (float -> triple promotion,
    /// point/vector/normal interchange); reports and returns nothing if it cannot.
    std::optional<Value> Convert(const Value& v, Type target, lang::SourceLoc loc, const std::string& what);

    void PushScope() { m_state.scopes.emplace_back(); }
    void PopScope();
    Variable* Find(const std::string& name);
    /// Find, or in a nested function a variable of the enclosing scopes (ImplicitExtern): every
    /// use of a name as a variable, read or written, goes through this.
    Variable* FindOrExtern(const std::string& name) {
        Variable* var = Find(name);
        return var ? var : ImplicitExtern(name);
    }
    IrBuilder& ir() { return m_out.ir; }
    ValueId True() { return ir().Const(1.0); }
    ValueId False() { return ir().Const(0.0); }
    int Line() const { return m_line; }
    /// A string is a compile-time constant: its index in m_strings.
    Value StringValue(const std::string& text);
    /// The text of a string value, if it is one constant string.
    std::optional<std::string> StringOf(const Value& v) const;
    /// The string a parameter of a function nobody calls holds while the function is checked
    /// (CheckUncalledFunctions): unknown, so a space name, spline basis or filterstep parameter
    /// taken from it is accepted there and checked at each call instead. No source string equals
    /// it (it holds a NUL).
    static const std::string& UnknownString();
    /// Whether `name` is UnknownString() while checking an uncalled function.
    bool Unknown(const std::string& name) const { return m_checkingOnly && name == UnknownString(); }

    LoweredShader& m_out;
    lang::Diagnostics& m_diags;
    ValueOps m_ops;
    FlowState m_state;
    /// The instance's parameter values (then parameters are constants), or null (registers).
    const std::vector<std::vector<double>>* m_paramValues;
    /// The instance's string parameter values, or null (defaults).
    const std::map<std::string, std::string>* m_stringValues;
    /// The instance's coordinate spaces, or null (all the identity).
    const Spaces* m_spaces;
    /// The instance's options and attributes, or null (no scene).
    const SceneFacts* m_facts;
    // The limits of lowering (diag/limits.h), read once per shader: iterations a loop with a
    // condition that varies over the surface is unrolled for (varying-loop-iterations), that a
    // loop with a constant condition may run (loop-iterations), operations the shader may ask for
    // (program-ops) and calls nested (call-depth).
    const int m_varyingLoopBudget;
    const int m_constantLoopBudget;
    const int64_t m_maxOps;
    const size_t m_maxCallDepth;
    std::vector<std::string> m_strings;
    /// Functions by visibility: (scope depth at definition, definition), innermost last.
    std::vector<std::pair<size_t, const lang::FunctionDef*>> m_functions;
    /// Functions being inlined, outermost first.
    std::vector<const lang::FunctionDef*> m_callStack;
    /// Per function being inlined: its caller's scopes (where `extern` looks) and the names it
    /// declared extern (written back after the call).
    struct ExternFrame {
        std::vector<std::unordered_map<std::string, Variable>>* callerScopes;
        std::vector<std::string> names;
    };
    std::vector<ExternFrame> m_externs;
    /// Declares `d` (extern) as an alias of the caller's variable of that name.
    void DeclareExtern(const lang::VarDecl& d);
    /// In a nested function, a variable of the enclosing scopes it names without declaring it
    /// extern: declared extern implicitly (as prman does), or null if there is none.
    Variable* ImplicitExtern(const std::string& name);
    using Scope = std::unordered_map<std::string, Variable>;
    /// For ImplicitExtern: in the nested function of call frame k, an alias in `params` (its
    /// parameter scope) of `name` from its caller's scopes, or, through callers that are nested
    /// functions too, from theirs; each caller on the way gets an alias too, so that a write goes
    /// back out one call at a time. Null if no enclosing scope has the name.
    Variable* AliasOuter(size_t k, const std::string& name, Scope& params);
    /// Functions defined inside the shader body or another function.
    std::unordered_set<const lang::FunctionDef*> m_nested;
    /// Every function defined, and those inlined at least once.
    std::vector<const lang::FunctionDef*> m_defined;
    std::unordered_set<const lang::FunctionDef*> m_called;
    /// Lowering a function nobody calls, for its diagnostics only.
    bool m_checkingOnly = false;
    void CheckUncalledFunctions();
    int m_line = 0;
    // True once the program-ops limit is passed (reported once, at `loc`, with a note on the loop
    // being unrolled): from then on statements are skipped and loops stop unrolling, so that the
    // limit is reached in time and memory proportional to it.
    bool TooLarge(const lang::SourceLoc& loc);
    bool m_reportedSize = false;
    std::vector<lang::SourceLoc> m_unrolling;  // the loops being unrolled, innermost last
    // Loops whose body has been checked as dead code (names, types) before their first unrolling.
    std::unordered_set<const lang::Stmt*> m_checkedLoops;
    std::unordered_set<const lang::Stmt*> m_endlessLoops;  // loops past loop-iterations (reported)
};

/// The names of the built-ins lower_extras.cpp and lower_surface.cpp lower.
std::vector<std::string> ExtraCallNames();
std::vector<std::string> SurfaceCallNames();

/// Lower() without an instance, with `observe` called on every expression the walk lowers
/// (each time: once per unrolled iteration, once per inlined call) and the Value it got. For
/// the test that the typed AST (typecheck.h) gives every expression the lowering's type.
std::optional<LoweredShader> LowerObserved(const lang::TranslationUnit& unit, lang::Diagnostics& diags,
                                           Lowerer::Observer observe);

}  // namespace affray::compiler
