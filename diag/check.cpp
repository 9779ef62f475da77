// diag/check.cpp: what a failed AFFRAY_CHECK prints (diag/check.h).
#include "diag/check.h"

#include <cstdio>
#include <cstdlib>

namespace affray::diag {

std::string CheckFailureMessage(const char* file, int line, const char* expression, const std::string& values) {
    std::string message =
        "affray: internal check failed at " + std::string(file) + ":" + std::to_string(line) + ": " + expression;
    if (!values.empty()) message += " (" + values + ")";
    return message + "\n";
}

void CheckFailed(const char* file, int line, const char* expression, const std::string& values) {
    const std::string message = CheckFailureMessage(file, line, expression, values);
    std::fputs(message.c_str(), stderr);
    std::fflush(stderr);
    std::abort();
}

}  // namespace affray::diag
