// diag/check.h: invariant checks for library code. A broken invariant is a bug in affray, not bad
// input (bad input is a diag::Diagnostic, decision 7 of docs/design.md): the check prints where
// it failed, the expression and its operands' values to stderr and aborts, so that a test, a
// fuzzer or a user's report points at the line.
//
//   AFFRAY_CHECK(cond), AFFRAY_CHECK_EQ(a, b) (and _NE, _LT, _LE, _GT, _GE): always checked.
//   AFFRAY_DCHECK(cond), AFFRAY_DCHECK_EQ(a, b), ...: checked in debug builds (no NDEBUG) and in
//   the sanitiser build (AFFRAY_DCHECKS, set by AFFRAY_SANITIZE); in Release the condition is
//   compiled (it must stay valid code) but never evaluated.
//
//   AFFRAY_CHECK_LT(index, size) fails as
//   "affray: internal check failed at vm/prune.cpp:72: index < size (index = 9, size = 4)".
#pragma once

#include <sstream>
#include <string>
#include <type_traits>

namespace affray::diag {

/// The message of a failed check: where, the expression, and the operands' values if given.
std::string CheckFailureMessage(const char* file, int line, const char* expression, const std::string& values);

/// Prints CheckFailureMessage to stderr and aborts.
[[noreturn]] void CheckFailed(const char* file, int line, const char* expression, const std::string& values);

/// A value as a check prints it: numbers and strings as written, a bool as true or false,
/// pointers as addresses, other types as "(unprintable)".
template <class T>
std::string CheckValue(const T& value) {
    if constexpr (std::is_same_v<T, bool>) {
        return value ? "true" : "false";
    } else if constexpr (requires(std::ostream & out) { out << value; }) {
        std::ostringstream out;
        out.precision(17);
        out << value;
        return out.str();
    } else {
        return "(unprintable)";
    }
}

/// "a = 1, b = 2" for the operands of a failed comparison.
template <class A, class B>
std::string CheckValues(const char* aText, const A& a, const char* bText, const B& b) {
    return std::string(aText) + " = " + CheckValue(a) + ", " + bText + " = " + CheckValue(b);
}

}  // namespace affray::diag

#define AFFRAY_CHECK(condition)                                                         \
    do {                                                                                \
        if (!(condition)) [[unlikely]]                                                  \
            ::affray::diag::CheckFailed(__FILE__, __LINE__, #condition, std::string()); \
    } while (false)

#define AFFRAY_CHECK_OP(a, op, b)                                                                           \
    do {                                                                                                    \
        const auto& affrayCheckA_ = (a);                                                                    \
        const auto& affrayCheckB_ = (b);                                                                    \
        if (!(affrayCheckA_ op affrayCheckB_)) [[unlikely]]                                                 \
            ::affray::diag::CheckFailed(__FILE__, __LINE__, #a " " #op " " #b,                              \
                                        ::affray::diag::CheckValues(#a, affrayCheckA_, #b, affrayCheckB_)); \
    } while (false)

#define AFFRAY_CHECK_EQ(a, b) AFFRAY_CHECK_OP(a, ==, b)
#define AFFRAY_CHECK_NE(a, b) AFFRAY_CHECK_OP(a, !=, b)
#define AFFRAY_CHECK_LT(a, b) AFFRAY_CHECK_OP(a, <, b)
#define AFFRAY_CHECK_LE(a, b) AFFRAY_CHECK_OP(a, <=, b)
#define AFFRAY_CHECK_GT(a, b) AFFRAY_CHECK_OP(a, >, b)
#define AFFRAY_CHECK_GE(a, b) AFFRAY_CHECK_OP(a, >=, b)

#if !defined(NDEBUG) || defined(AFFRAY_DCHECKS)
#define AFFRAY_DCHECK_IS_ON 1
#define AFFRAY_DCHECK(condition) AFFRAY_CHECK(condition)
#define AFFRAY_DCHECK_OP(a, op, b) AFFRAY_CHECK_OP(a, op, b)
#else
#define AFFRAY_DCHECK_IS_ON 0
// Compiled, so that it stays valid code, but never evaluated.
#define AFFRAY_DCHECK(condition)      \
    do {                              \
        if (false) (void)(condition); \
    } while (false)
#define AFFRAY_DCHECK_OP(a, op, b)   \
    do {                             \
        if (false) (void)((a)op(b)); \
    } while (false)
#endif

#define AFFRAY_DCHECK_EQ(a, b) AFFRAY_DCHECK_OP(a, ==, b)
#define AFFRAY_DCHECK_NE(a, b) AFFRAY_DCHECK_OP(a, !=, b)
#define AFFRAY_DCHECK_LT(a, b) AFFRAY_DCHECK_OP(a, <, b)
#define AFFRAY_DCHECK_LE(a, b) AFFRAY_DCHECK_OP(a, <=, b)
#define AFFRAY_DCHECK_GT(a, b) AFFRAY_DCHECK_OP(a, >, b)
#define AFFRAY_DCHECK_GE(a, b) AFFRAY_DCHECK_OP(a, >=, b)
