// rib/conditional.cpp: conditional RIB (prman 13.5 and later, which RenderMan for Maya and other
// exporters write for render passes): IfBegin "expression", ElseIf "expression", Else, IfEnd.
// The expressions test the values of options and attributes, named "$category:name" (Option
// "user" "string pass_class" ["Final"] is $user:pass_class; an attribute of that name wins over
// the option), and the requests of the branches not taken are dropped as they are read, before
// an object definition records them. Conditionals nest, may span archives, and are evaluated
// only on the branch being read, so a branch not taken may test what is not defined.
//
// The expression language, the subset of prman's that exporters write: numbers, strings in
// single (or double) quotes, $name and ${name}, defined(name), concat(a, b, ...), the
// arithmetic operators + - * /, comparisons == != < <= > >= (numbers with numbers, strings with
// strings), ! && || and parentheses. A value is true if it is a nonzero number or a non-empty
// string. Anything else (such as prman's =~ pattern match) is an error at the request.
#include <cctype>
#include <cmath>
#include <functional>
#include <optional>
#include <sstream>

#include "rib/parser.h"

namespace affray::rib {
namespace {

struct Value {
    bool isString = false;
    double number = 0;
    std::string text;

    bool TrueP() const { return isString ? !text.empty() : number != 0; }
    static Value Number(double x) { return {false, x, {}}; }
    static Value String(std::string s) { return {true, 0, std::move(s)}; }
};

/// Evaluates one expression by recursive descent; Lookup finds a variable (null: undefined).
/// Each method returns nothing after setting m_problem.
class Evaluator {
  public:
    using Lookup = std::function<const ParamValue*(const std::string&)>;
    Evaluator(std::string_view text, Lookup lookup) : m_text(text), m_lookup(std::move(lookup)) {}

    /// The expression's truth, or nothing with *problem saying why.
    std::optional<bool> Run(std::string* problem) {
        std::optional<Value> v = Or();
        Skip();
        if (v && m_pos < m_text.size()) v = Problem("unexpected '" + std::string(m_text.substr(m_pos)) + "'");
        if (!v) {
            *problem = m_problem;
            return std::nullopt;
        }
        return v->TrueP();
    }

  private:
    std::optional<Value> Problem(std::string problem) {
        if (m_problem.empty()) m_problem = std::move(problem);
        return std::nullopt;
    }
    void Skip() {
        while (m_pos < m_text.size() && std::isspace(static_cast<unsigned char>(m_text[m_pos]))) ++m_pos;
    }
    /// Consumes `op` if it comes next (and is not the start of a longer operator in `notBefore`).
    bool Accept(std::string_view op, char notBefore = '\0') {
        Skip();
        if (m_text.substr(m_pos, op.size()) != op) return false;
        if (notBefore && m_pos + op.size() < m_text.size() && m_text[m_pos + op.size()] == notBefore) return false;
        m_pos += op.size();
        return true;
    }
    std::optional<Value> Or() {
        std::optional<Value> left = And();
        while (left && Accept("||")) {
            std::optional<Value> right = And();
            if (!right) return right;
            left = Value::Number(left->TrueP() || right->TrueP());
        }
        return left;
    }
    std::optional<Value> And() {
        std::optional<Value> left = Comparison();
        while (left && Accept("&&")) {
            std::optional<Value> right = Comparison();
            if (!right) return right;
            left = Value::Number(left->TrueP() && right->TrueP());
        }
        return left;
    }
    std::optional<Value> Comparison() {
        std::optional<Value> left = Sum();
        if (!left) return left;
        static const char* const kOps[] = {"==", "!=", "<=", ">=", "<", ">"};
        for (const char* op : kOps) {
            if (!Accept(op)) continue;
            std::optional<Value> right = Sum();
            if (!right) return right;
            if (left->isString != right->isString)
                return Problem(std::string("'") + op + "' compares a number with a string");
            int order = left->isString ? left->text.compare(right->text) : 0;
            if (!left->isString) order = left->number < right->number ? -1 : left->number > right->number ? 1 : 0;
            const std::string_view o = op;
            bool result = order > 0;  // ">"
            if (o == "==") result = order == 0;
            if (o == "!=") result = order != 0;
            if (o == "<=") result = order <= 0;
            if (o == ">=") result = order >= 0;
            if (o == "<") result = order < 0;
            return Value::Number(result);
        }
        Skip();
        if (m_text.substr(m_pos, 2) == "=~") return Problem("the pattern match '=~' is not supported");
        return left;
    }
    std::optional<Value> Sum() {
        std::optional<Value> left = Product();
        while (left) {
            const char op = Accept("+") ? '+' : Accept("-") ? '-' : '\0';
            if (!op) break;
            std::optional<Value> right = Product();
            if (!right) return right;
            if (left->isString || right->isString)
                return Problem(std::string("'") + op + "' needs numbers (concat() joins strings)");
            left = Value::Number(op == '+' ? left->number + right->number : left->number - right->number);
        }
        return left;
    }
    std::optional<Value> Product() {
        std::optional<Value> left = Unary();
        while (left) {
            const char op = Accept("*") ? '*' : Accept("/") ? '/' : '\0';
            if (!op) break;
            std::optional<Value> right = Unary();
            if (!right) return right;
            if (left->isString || right->isString) return Problem(std::string("'") + op + "' needs numbers");
            left = Value::Number(op == '*' ? left->number * right->number : left->number / right->number);
        }
        return left;
    }
    std::optional<Value> Unary() {
        // Parentheses and unary operators recurse: a bound keeps a hostile file off the stack.
        if (++m_depth > kMaxDepth)
            return Problem("the expression nests more than " + std::to_string(kMaxDepth) + " deep");
        std::optional<Value> v = UnaryOperand();
        --m_depth;
        return v;
    }
    std::optional<Value> UnaryOperand() {
        if (Accept("!", '=')) {
            std::optional<Value> v = Unary();
            return v ? std::optional<Value>(Value::Number(!v->TrueP())) : v;
        }
        if (Accept("-")) {
            std::optional<Value> v = Unary();
            if (v && v->isString) return Problem("'-' needs a number");
            return v ? std::optional<Value>(Value::Number(-v->number)) : v;
        }
        return Primary();
    }
    /// A name of letters, digits, '_', ':' and '.'.
    std::string Name() {
        Skip();
        const size_t begin = m_pos;
        while (m_pos < m_text.size() && (std::isalnum(static_cast<unsigned char>(m_text[m_pos])) ||
                                         m_text[m_pos] == '_' || m_text[m_pos] == ':' || m_text[m_pos] == '.'))
            ++m_pos;
        return std::string(m_text.substr(begin, m_pos - begin));
    }
    std::optional<Value> Variable(const std::string& name) {
        if (name.empty()) return Problem("'$' needs a name");
        const ParamValue* p = m_lookup(name);
        if (!p) return Problem("no option or attribute '" + name + "' is defined (test it with defined(" + name + "))");
        if (p->strings.size() + p->numbers.size() != 1)
            return Problem("'" + name + "' holds " + std::to_string(p->strings.size() + p->numbers.size()) +
                           " values, not one");
        return p->strings.empty() ? Value::Number(p->numbers[0]) : Value::String(p->strings[0]);
    }
    std::optional<Value> Primary() {
        Skip();
        if (m_pos >= m_text.size()) return Problem("the expression ends too soon");
        const char c = m_text[m_pos];
        if (c == '(') {
            ++m_pos;
            std::optional<Value> v = Or();
            if (v && !Accept(")")) return Problem("'(' has no matching ')'");
            return v;
        }
        if (c == '\'' || c == '"') {
            const size_t end = m_text.find(c, m_pos + 1);
            if (end == std::string_view::npos) return Problem("unterminated string");
            Value v = Value::String(std::string(m_text.substr(m_pos + 1, end - m_pos - 1)));
            m_pos = end + 1;
            return v;
        }
        if (c == '$') {
            ++m_pos;
            if (!Accept("{")) return Variable(Name());
            const std::string name = Name();
            if (!Accept("}")) return Problem("'${' has no matching '}'");
            return Variable(name);
        }
        if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') {
            const std::string rest(m_text.substr(m_pos));
            char* end = nullptr;
            const double x = std::strtod(rest.c_str(), &end);
            if (end == rest.c_str() || !std::isfinite(x)) return Problem("malformed number");
            m_pos += static_cast<size_t>(end - rest.c_str());
            return Value::Number(x);
        }
        const std::string word = Name();
        if (word == "defined") {
            if (!Accept("(")) return Problem("defined needs a name in parentheses");
            const std::string name = Name();
            if (name.empty() || !Accept(")")) return Problem("defined needs a name in parentheses");
            return Value::Number(m_lookup(name) != nullptr);
        }
        if (word == "concat") {
            if (!Accept("(")) return Problem("concat needs its arguments in parentheses");
            std::string text;
            do {
                std::optional<Value> v = Or();
                if (!v) return v;
                std::ostringstream number;  // as messages print numbers
                number << v->number;
                text += v->isString ? v->text : number.str();
            } while (Accept(","));
            if (!Accept(")")) return Problem("concat needs its arguments in parentheses");
            return Value::String(text);
        }
        if (word.empty()) return Problem("unexpected '" + std::string(m_text.substr(m_pos)) + "'");
        return Problem("unknown word '" + word + "' (a variable is written $" + word + ")");
    }

    static constexpr int kMaxDepth = 200;
    std::string_view m_text;
    Lookup m_lookup;
    size_t m_pos = 0;
    int m_depth = 0;
    std::string m_problem;
};

}  // namespace

const ParamValue* RibParser::FindSetting(const std::string& name) const {
    if (m_state.attributes)
        if (auto it = m_state.attributes->find(name); it != m_state.attributes->end()) return &it->second;
    if (auto it = m_options.find(name); it != m_options.end()) return &it->second;
    return nullptr;
}

bool RibParser::Condition(const RibRequest& r, bool evaluate, bool* out) {
    if (r.args.size() != 1 || r.args[0].isArray || !r.args[0].StringsP())
        return Fail(r.at, Quote(r.name) + " expects one string (an expression)");
    if (!evaluate) return true;
    const std::string& text = r.args[0].strings[0];
    std::string problem;
    std::optional<bool> value =
        Evaluator(text, [this](const std::string& name) { return FindSetting(name); }).Run(&problem);
    if (!value) return Fail(r.args[0].at, Quote(r.name) + " expression \"" + text + "\": " + problem);
    *out = *value;
    return true;
}

bool RibParser::Conditional(const RibRequest& r, bool* consumed) {
    const bool open = !m_conditionals.empty();
    const bool reading = !open || m_conditionals.back().active;  // this branch is read
    *consumed = true;
    if (r.name == "IfBegin") {
        // Inside a branch not taken nothing is evaluated, and no branch of this one is taken.
        bool value = false;
        if (!Condition(r, reading, &value)) return false;
        m_conditionals.push_back({r.at, value, !reading || value, false});
        return true;
    }
    if (r.name == "ElseIf" || r.name == "Else" || r.name == "IfEnd") {
        if (!open) return Fail(r.at, Quote(r.name) + " without matching 'IfBegin'");
        OpenConditional& c = m_conditionals.back();
        if (r.name == "IfEnd") {
            if (!NoArgs(r)) return false;
            m_conditionals.pop_back();
            return true;
        }
        if (c.elseSeen)
            return Fail(r.at, Quote(r.name) + " after the 'Else' of the 'IfBegin' on " + LineName(c.at, r.at));
        bool value = true;
        if (r.name == "Else") {
            if (!NoArgs(r)) return false;
            c.elseSeen = true;
        } else if (!Condition(r, !c.taken, &value)) {
            return false;
        }
        c.active = !c.taken && value;
        c.taken = c.taken || c.active;
        return true;
    }
    *consumed = !reading;
    return true;
}

}  // namespace affray::rib
