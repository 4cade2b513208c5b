#pragma once
// What the chain did to one view, as `keyturn describe --explain` prints it (and the
// Python module's explain=True): the input kind, each filter step's effect, the
// working resolution, and the points, resolution and K that were described.
#include <string>

#include "keyturn/core/descriptor.h"

namespace keyturn {

// Lines ending in '\n'; `name` (the file) heads the first.
std::string explainView(const std::string& name, const ViewDescriptor& d);

}  // namespace keyturn
