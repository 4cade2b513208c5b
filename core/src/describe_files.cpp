#include "keyturn/core/describe_files.h"

#include <optional>
#include <sstream>

#include "keyturn/core/cloud_io.h"
#include "keyturn/core/empty_view.h"
#include "keyturn/core/error.h"
#include "keyturn/core/parallel_for.h"
#include "keyturn/core/view_explanation.h"
#include "keyturn/core/view_report.h"

namespace keyturn {
namespace {

// What one file gave: its row, or the reason it gave none, and what the user should be told.
struct FileResult {
  std::optional<std::string> row;
  std::string error, flags, explained;
  int low_keypoints = 0;  // the count when it is below the threshold, else 0
};

FileResult describeFile(const std::string& file, const DescribeFilesOptions& o) {
  FileResult r;
  try {
    const Cloud cloud = loadCloud(file, o.depth);
    if (o.descriptor.filter && isDepthImagePath(file)) checkDepthScale(file, cloud, o.depth.depth_scale, o.descriptor.filter_options);
    const ViewDescriptor d = describeView(cloud, o.descriptor);
    r.row = describeCsvRow(file, d);
    r.low_keypoints = d.low_keypoints ? d.keypointCount() : 0;
    r.flags = d.filter.flaggedSummary();
    if (o.explain) r.explained = explainView(file, d);
  } catch (const DepthScaleError& e) {
    r.error = o.depth_scale_message ? file + ": " + o.depth_scale_message(e) : e.what();
  } catch (const Error& e) {
    const std::string msg = e.what();
    r.error = msg.rfind(file, 0) == 0 ? msg : file + ": " + msg;  // name the file once
    const std::string& hint = dynamic_cast<const FilteredAwayError*>(&e)        ? o.explain_hint
                              : dynamic_cast<const MissingIntrinsicsError*>(&e) ? o.intrinsics_hint
                                                                                : std::string();
    if (!hint.empty()) r.error += " (" + hint + ")";
  } catch (const std::exception& e) {
    r.error = file + ": unexpected failure: " + e.what();
  }
  return r;
}

}  // namespace

DescribedFiles describeFiles(const std::vector<std::string>& files, const DescribeFilesOptions& o,
                             const std::function<void()>& done) {
  std::vector<FileResult> results(files.size());
  parallelFor(files.size(), o.jobs, [&](std::size_t i) {
    results[i] = describeFile(files[i], o);
    if (done) done();
  });

  DescribedFiles out;
  std::ostringstream csv;
  csv << describeCsvHeader(o.descriptor.features, o.descriptor.histogram.bins) << "\n";
  for (std::size_t i = 0; i < files.size(); ++i) {
    const FileResult& r = results[i];
    if (r.row) {
      csv << *r.row << "\n";
      ++out.described;
    } else {
      ++out.failed;
    }
    if (!r.explained.empty()) out.messages.push_back(r.explained);
    if (!r.error.empty()) out.messages.push_back(o.prefix + r.error + "\n");
    if (!r.flags.empty())
      out.messages.push_back(o.prefix + "warning: " + files[i] + ": " + r.flags + (o.explain_hint.empty() ? "" : " (" + o.explain_hint + ")") + "\n");
    if (r.low_keypoints) {
      ++out.flagged;
      if (o.warn_low)
        out.messages.push_back(o.prefix + "warning: " + files[i] + ": only " + std::to_string(r.low_keypoints) +
                               " keypoints (< " + std::to_string(o.descriptor.low_keypoints) +
                               "): its histograms are thin\n");
    }
  }
  out.csv = csv.str();
  return out;
}

}  // namespace keyturn
