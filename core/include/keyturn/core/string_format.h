#pragma once
// printf-style formatting into a std::string, for the reports and tables the
// tools print (their column layouts are printf's), comma-separated numbers
// as the tools take them ("0,45,90"), and a file's bytes made fit for a message.
#include <string>
#include <vector>

namespace keyturn {

// Appends the formatted text to out (any length).
void appendFormat(std::string& out, const char* format, ...) __attribute__((format(printf, 2, 3)));

// Throws keyturn::Error "WHAT: 'x' is not a number" (the whole item must be one) or
// "WHAT: no number given".
std::vector<double> parseNumberList(const std::string& text, const std::string& what);

// `text` with every byte that is not printable UTF-8 (a control character, or a byte of no valid
// UTF-8 sequence) written as \xHH: a message quoting a file's bytes stays one line of valid UTF-8,
// which a terminal shows as it is and Python decodes ('\xff\xfe' stays readable, not raw bytes).
std::string printableText(const std::string& text);

}  // namespace keyturn
