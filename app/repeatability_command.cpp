// keyturn repeatability: absolute and relative keypoint repeatability against ε
// for several detectors, native and at an equal keypoint budget, over pairs of
// posed views (a calibrated dataset or a pose file). The study and its plots are
// core's; this parses, calls, draws and prints.
#include <iostream>
#include <memory>

#include "commands.h"
#include "depth_image_options.h"
#include "keyturn/core/durable_file.h"
#include "keyturn/core/pose_list.h"
#include "keyturn/studies/repeatability_study.h"
#include "keyturn/dataset/study_views.h"
#include "keyturn/plots/report_plots.h"
#include "progress.h"
#include "study_options.h"

namespace keyturn::app {
namespace {

struct RepArgs {
  std::string input, out, pose_format = "auto", views;
  std::string detectors = "iss,harris3d,sift3d,uniform";
  std::string eps = "0.5:3:0.25";
  std::string pairs = pairRuleName(PairRule());
  StudyOptions study;
  PoseReadOptions poses;
  DepthImageFlags depth;
  bool json = false, no_filter = false;
};

int runRepeatability(RepArgs a) {
  a.study.detectors = parseDetectorList(a.detectors);
  a.study.eps_res = parseEpsList(a.eps);
  a.study.pairs = parsePairRule(a.pairs);
  a.study.filter = !a.no_filter;
  a.study.depth = a.depth.toOptions();
  a.poses.format = parsePoseFormat(a.pose_format);
  a.poses.views = a.views;
  std::unique_ptr<Progress> bar;
  StudyProgress progress{[&](const std::string& stage, std::size_t n) { bar = std::make_unique<Progress>(stage, n, !a.json); },
                         [&] { bar->advance(); }, [&] { bar->finish(); }};
  std::vector<StudyView> views;
  try {
    views = dataset::studyViews(a.input, a.poses);
  } catch (const MissingViewListError& e) {
    throw Error(std::string(e.what()) + " (--views LIST)");
  }
  Study s;
  try {
    s = runRepeatabilityStudy(std::move(views), a.study, progress);
  } catch (const NoOverlapError& e) {  // the remedies are this command's flags
    throw Error(std::string(e.what()) + (e.inverse_overlaps ? " (--invert-poses)" : " (--pose-format)") +
                "; --force scores anyway");
  }

  std::filesystem::create_directories(a.out);
  const std::string md = studyMarkdown(s, a.input), json = studyJson(s, a.input);
  writeFileDurably(a.out + "/repeatability.csv", studyCsv(s));
  writeFileDurably(a.out + "/pairs.csv", studyPairsCsv(s));
  writeFileDurably(a.out + "/summary.md", md);
  writeFileDurably(a.out + "/summary.json", json);
  plots::saveReportPlots(studyPlots(s), a.out);
  std::cout << (a.json ? json : md + "Report: " + a.out + "\n");
  return 0;
}

}  // namespace

Command addRepeatabilityCommand(CLI::App& app) {
  auto a = std::make_shared<RepArgs>();
  auto* cmd = app.add_subcommand("repeatability", "Keypoint repeatability of several detectors against ε");
  cmd->add_option("input", a->input, "A calibrated keyturn dataset, or a pose file (docs/repeatability.md)")->required();
  cmd->add_option("--pose-format", a->pose_format, "auto, keyturn, stanford, tum or matrix")->capture_default_str();
  cmd->add_option("--views", a->views, "TUM only: the view files, one FILE or TIMESTAMP FILE a line");
  cmd->add_flag("--invert-poses", a->poses.invert, "The poses map the common frame into each view: invert them");
  cmd->add_option("--detectors", a->detectors, "Comma list: iss, harris3d, sift3d, uniform, iss-chain (the keypoints describe outputs by default), iss-refined, iss-nearest, iss-salient (the chain's keypoints with --refine-keypoints or --keypoint-placement), iss-measured (ISS on the measured points at the chain's scale: --keypoint-placement measured)")->capture_default_str();
  cmd->add_option("--eps", a->eps, "ε as START:STOP:STEP or a list, in multiples of the resolution")->capture_default_str();
  cmd->add_option("--pairs", a->pairs, "consecutive, from-first or all-within:DEG")->capture_default_str();
  cmd->add_option("--keypoints", a->study.keypoints, "Equal budget K for every detector (0: ISS's count per view)")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  auto& iss = a->study.detector.iss;
  cmd->add_option("--iss-frame", iss.frame_radius, "ISS scatter radius r_frame (× resolution)")->capture_default_str()->check(CLI::PositiveNumber);
  cmd->add_option("--iss-nms", iss.nms_radius, "ISS non-maximum radius (× resolution)")->capture_default_str()->check(CLI::PositiveNumber);
  cmd->add_option_function<double>("--iss-gamma", [&iss](double g) { iss.gamma21 = iss.gamma32 = g; },
                                   "ISS eigenvalue-ratio thresholds γ21 = γ32 (default 0.975)")
      ->check(CLI::Range(1e-9, 1.0));
  cmd->add_flag("--force", a->study.force, "Score even when the poses give (almost) no overlap between views");
  cmd->add_flag("--icp", a->study.icp, "Refine each pair's ground truth by ICP (residual reported)");
  cmd->add_flag("--no-filter", a->no_filter, "Use the views as they are");
  a->depth.add(*cmd);
  cmd->add_option("--out,-o", a->out, "Report folder (CSV, Markdown, JSON, PNG plots)")->required();
  cmd->add_flag("--json", a->json, "Print the summary as JSON");
  return {cmd, [a] { return runRepeatability(*a); }};
}

}  // namespace keyturn::app
