#pragma once
// printf-style formatting into a std::string, for the reports and tables the
// tools print (their column layouts are printf's).
#include <string>

namespace keyturn {

// Appends the formatted text to out (any length).
void appendFormat(std::string& out, const char* format, ...) __attribute__((format(printf, 2, 3)));

}  // namespace keyturn
