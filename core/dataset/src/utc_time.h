#pragma once
#include <string>

namespace keyturn::dataset {

// Now as ISO 8601 UTC with milliseconds, "2026-11-22T00:32:35.508Z": a view's captured_at, a
// dataset's creation, when a writer took the dataset's lock.
std::string isoNow();

}  // namespace keyturn::dataset
