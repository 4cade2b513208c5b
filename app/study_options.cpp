#include "study_options.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "keyturn/core/error.h"
#include "keyturn/core/string_format.h"

namespace keyturn::app {

std::vector<double> parseEpsList(const std::string& s) {
  std::vector<double> out;
  if (s.find(':') != std::string::npos) {
    std::string list = s;
    std::replace(list.begin(), list.end(), ':', ',');
    const std::vector<double> abc = parseNumberList(list, "--eps");
    if (abc.size() != 3 || !(abc[2] > 0) || abc[1] < abc[0])
      throw Error("--eps: expected START:STOP:STEP with START <= STOP and STEP > 0, got '" + s + "'");
    for (int i = 0; abc[0] + i * abc[2] <= abc[1] + 1e-9; ++i) out.push_back(abc[0] + i * abc[2]);  // no summed rounding
  } else {
    out = parseNumberList(s, "--eps");
  }
  for (double e : out)
    if (!(e > 0) || !std::isfinite(e)) throw Error("--eps: each ε must be a positive multiple of the resolution, got '" + s + "'");
  return out;
}

std::vector<Detector> parseDetectorList(const std::string& text) {
  std::vector<Detector> out;
  std::istringstream ss(text);
  for (std::string t; std::getline(ss, t, ',');) out.push_back(parseDetector(t));
  if (out.empty()) throw Error("--detectors: no detector named");
  return out;
}

}  // namespace keyturn::app
