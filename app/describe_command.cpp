// keyturn describe: one CSV row per view with its keypoint count and the PDF
// bins of every requested keypoint/shape function. Files run in parallel; a bad
// file is reported and skipped, the good rows are still written, and the exit
// code says something failed.
#include <filesystem>
#include <iostream>

#include "commands.h"
#include "cached_features.h"
#include "depth_image_options.h"
#include "descriptor_options.h"
#include "keyturn/core/describe_files.h"
#include "keyturn/core/durable_file.h"
#include "keyturn/core/error.h"
#include "keyturn/core/view_files.h"
#include "learning_options.h"
#include "progress.h"

namespace keyturn::app {
namespace {

struct DescribeArgs {
  std::vector<std::string> inputs;
  std::string out;
  int jobs = 0;
  bool quiet = false;
  bool explain = false;  // each filter step's effect per view, on stderr
  bool cache = false;  // dataset mode: fill the dataset's feature cache
  std::string shard;  // "I/N": dataset mode, this process's share of the views
  DescriptorFlags flags;
  DepthImageFlags depth;
};

// A dataset folder: fill its feature cache (or this shard of it) for evaluate/train/consistency.
int runDescribeDataset(const DescribeArgs& a) {
  const auto [shard, shards] = a.shard.empty() ? std::pair<int, int>{0, 1} : parseShard(a.shard);
  const std::string& dataset = a.inputs.front();
  DescribeProgressLine progress(a.quiet);
  const learning::FeatureCache cache{dataset, datasetViews(dataset), a.flags.options, a.jobs, &progress};
  const std::string path = shards > 1 ? learning::describeCacheShard(cache, shard, shards)
                                      : (learning::loadOrDescribeCache(cache), learning::featureCachePath(dataset, cache.options));
  if (!a.quiet) std::cerr << "keyturn describe: feature cache → " << path << "\n";
  return 0;
}

int runDescribe(const DescribeArgs& a) {
  if (a.cache || !a.shard.empty()) {
    if (a.inputs.size() != 1 || !isDataset(a.inputs.front()))
      throw Error(std::string(a.cache ? "--cache" : "--shard") + " needs one dataset folder (one with manifest.csv)");
    return runDescribeDataset(a);
  }
  DescribeFilesOptions o;
  o.descriptor = a.flags.toOptions();
  o.depth = a.depth.toOptions();
  o.explain = a.explain;
  o.warn_low = !a.quiet;
  o.jobs = a.jobs;
  o.prefix = "keyturn describe: ";
  o.explain_hint = "--explain shows why";
  o.intrinsics_hint = kIntrinsicsHint;
  o.depth_scale_message = depthScaleMessage;
  ViewFileList list = collectViewFiles(a.inputs, o.depth.intrinsics.has_value());
  for (const auto& e : list.errors) std::cerr << o.prefix << e << "\n";
  const std::size_t n = list.files.size();
  Progress progress("describe", n, !a.quiet && n > 1);
  const DescribedFiles d = describeFiles(list.files, o, [&] { progress.advance(); });
  progress.finish();
  for (const auto& m : d.messages) std::cerr << m;
  const bool to_stdout = a.out.empty() || a.out == "-";
  if (to_stdout) std::cout << d.csv;
  else writeFileDurably(a.out, d.csv);
  if (!a.quiet)
    std::cerr << o.prefix << d.described << " of " << n << " views described"
              << (d.flagged ? ", " + std::to_string(d.flagged) + " flagged for few keypoints" : "")
              << (to_stdout ? "" : " → " + a.out) << "\n";
  return d.failed + list.errors.size() == 0 ? 0 : 1;
}

}  // namespace

Command addDescribeCommand(CLI::App& app) {
  auto args = std::make_shared<DescribeArgs>();
  auto* cmd = app.add_subcommand("describe", "Describe views by keypoint/shape-function PDFs (CSV)");
  cmd->add_option("inputs", args->inputs, "PCD/PLY files, 16-bit depth PNGs, or folders of them")->required();
  cmd->add_option("--out,-o", args->out, "CSV file to write (default: standard output)");
  cmd->add_option("--jobs,-j", args->jobs, "Parallel files (default: all cores)");
  cmd->add_flag("--quiet,-q", args->quiet, "No progress or summary");
  cmd->add_flag("--explain", args->explain,
                "Print, per view, the input kind and what each filter step and the working resolution removed");
  cmd->add_flag("--cache", args->cache,
                "With a dataset folder: fill its feature cache (every block evaluate, train and consistency use)");
  cmd->add_option("--shard", args->shard,
                  "With a dataset folder: fill only the cache shard of views i ≡ I-1 (mod N) into a shard of the feature "
                  "cache (I/N, for array jobs; the shards merge when all are present)");
  args->flags.add(*cmd);
  args->depth.add(*cmd);
  return {cmd, [args] { return runDescribe(*args); }};
}

}  // namespace keyturn::app
