#pragma once
// printf-style formatting into a std::string, for the reports and tables the
// tools print (their column layouts are printf's), and comma-separated numbers
// as the tools take them ("0,45,90").
#include <string>
#include <vector>

namespace keyturn {

// Appends the formatted text to out (any length).
void appendFormat(std::string& out, const char* format, ...) __attribute__((format(printf, 2, 3)));

// Throws keyturn::Error "WHAT: 'x' is not a number" (the whole item must be one) or
// "WHAT: no number given".
std::vector<double> parseNumberList(const std::string& text, const std::string& what);

}  // namespace keyturn
