#pragma once
// How far a view's description moves when the view changes by what should not matter — a rigid
// motion, a resampling, jitter far below the sensor's noise — against how far apart the
// descriptions of different views are (docs/descriptors.md, "Stability"). Per function: every
// keypoint function, its scaled twin, Osada's functions, and PCL's ESF and VFH on the same views.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "keyturn/core/cloud.h"
#include "keyturn/core/descriptor.h"
#include "keyturn/core/report_plot_specs.h"
#include "keyturn/studies/view_perturbation.h"

namespace keyturn {

struct StabilityView {
  std::string name;   // shown in reports
  std::string group;  // views of one object share a group: between-view distances pair different groups
  Cloud cloud;
};

// Which cloud PCL's ESF and VFH describe. Given: the view's finite points as the user has them (an
// object cut: what a PCL user passes to ESF; the figure PCL gives). Filtered: the view after
// keyturn's filter, without the working resolution (the study's protocol until 2026-12-06).
enum class PclInput { Given, Filtered };
const char* pclInputName(PclInput input);
PclInput pclInputNamed(const std::string& name);  // throws keyturn::Error naming the choices

struct StabilityOptions {
  DescriptorOptions descriptor;  // its features are the functions studied (and their scaled twins when asked)
  std::vector<Perturbation> perturbations = standardPerturbations();
  int repetitions = 3;           // draws of each perturbation per view (seeds seed, seed+1, …)
  std::uint64_t seed = 1;
  bool pcl_descriptors = true;   // ESF (seeded) and VFH
  PclInput pcl_input = PclInput::Given;
  double vfh_normal_radius = 0.012;  // metres, as the learning peers use (kNormalRadius)
  int jobs = 0;                  // views described in parallel (0: one per core)
};

// One function's distances: [perturbation][draw over views] and between different views.
struct FunctionStability {
  std::string name;   // "kpd2", "s_kpd2", "d2", "esf", …
  bool keypoint = false;
  std::vector<std::vector<double>> l1, chi2;
  std::vector<double> between_l1, between_chi2;
  double medianL1(std::size_t perturbation) const;
  double betweenMedianL1() const;
  double ratio(std::size_t perturbation) const;  // median perturbed L1 ÷ median between-view L1
  double ratioOverall() const;                     // all non-rigid draws together
  double rigidMaxL1() const;                       // the largest L1 a rigid motion gave (NaN: none)
  double rigidShareWithin(double l1) const;        // the share of rigid draws with L1 ≤ l1 (NaN: none)
  std::vector<Perturbation> perturbations;         // copied from the study, for the rigid flags
};

struct StabilityStudy {
  std::vector<std::string> views;
  std::vector<Perturbation> perturbations;
  std::vector<FunctionStability> functions;
  std::vector<std::vector<int>> keypoint_change;  // [perturbation][draw] K(perturbed) − K(original)
  std::vector<int> not_described;                 // [perturbation] draws whose perturbed view failed
  std::vector<std::string> errors;                // "VIEW: what was wrong" for views left out
  int repetitions = 0;
  bool pcl_descriptors = false;
  PclInput pcl_input = PclInput::Given;
  int maxAbsKeypointChange(bool rigid) const;
  int maxAbsKeypointChangeUnder(const std::string& perturbation) const;  // -1: no such perturbation
};

struct StabilityProgress {
  std::function<void(std::size_t total)> begin = [](std::size_t) {};
  std::function<void()> step = [] {};
  std::function<void()> end = [] {};
};

// Describes every view and its perturbations. A view that cannot be described is left out with
// its reason in `errors`; throws keyturn::Error when fewer than two views can be described.
StabilityStudy runStabilityStudy(const std::vector<StabilityView>& views, const StabilityOptions& options,
                                 const StabilityProgress& progress = {});

std::string stabilityMarkdown(const StabilityStudy& study, const std::string& input);
std::string stabilityJson(const StabilityStudy& study, const std::string& input);
// stability_ratio.png (ratio per function and perturbation, log scale) and stability_rigid.png.
ReportPlots stabilityPlots(const StabilityStudy& study);

}  // namespace keyturn
