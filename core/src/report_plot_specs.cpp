#include "keyturn/core/report_plot_specs.h"

#include <cctype>

namespace keyturn {

std::string fileSafeName(std::string s) {
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
  return s;
}

}  // namespace keyturn
