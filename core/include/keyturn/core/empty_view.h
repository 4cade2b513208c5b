#pragma once
// A view with too little in it to describe: no points, none valid, fewer than three left after
// the filter, or fewer keypoints than the descriptor needs. Recognition answers "no object" for
// it (nothing on the table, or too little of it in view), not "unknown" (issue 34).
#include "keyturn/core/error.h"

namespace keyturn {

class EmptyViewError : public Error {
 public:
  using Error::Error;
};

// The filter left fewer than three points: each step's effect (explainView) says which removed them.
class FilteredAwayError : public EmptyViewError {
 public:
  using EmptyViewError::EmptyViewError;
};

}  // namespace keyturn
