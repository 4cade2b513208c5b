#pragma once
// Many view files described as `keyturn describe` reports them: in parallel, a bad
// file reported and skipped while the good rows are kept, messages in file order.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "keyturn/core/depth_image.h"
#include "keyturn/core/depth_scale_check.h"
#include "keyturn/core/descriptor.h"

namespace keyturn {

struct DescribeFilesOptions {
  DescriptorOptions descriptor;
  DepthImageOptions depth;
  bool explain = false;    // each view's filter explanation among the messages
  bool warn_low = true;    // a warning per view with fewer than descriptor.low_keypoints keypoints
  int jobs = 0;            // parallel files (0: all cores)
  std::string prefix;      // put before every one-line message (the command's name)
  // A front end's own remedies, in its words (core names none of its options): put in brackets
  // after a flagged filter step's warning and the error of a view the filter emptied (how to see
  // each step), and after the error of a depth image without intrinsics (how to give them).
  std::string explain_hint, intrinsics_hint;
  // A depth image whose scale leaves (almost) nothing in the range crop (core/depth_scale_check.h)
  // said in the front end's words (after "FILE: "); empty: core's own message.
  std::function<std::string(const DepthScaleError&)> depth_scale_message;
};

struct DescribedFiles {
  std::string csv;                    // header and one row per described view
  std::vector<std::string> messages;  // errors, warnings and explanations, each ending in '\n'
  std::size_t described = 0;
  std::size_t failed = 0;
  std::size_t flagged = 0;  // described, but with few keypoints
};

// `done` is called once per file as it finishes (from worker threads; may be empty).
DescribedFiles describeFiles(const std::vector<std::string>& files, const DescribeFilesOptions& o,
                             const std::function<void()>& done = {});

}  // namespace keyturn
