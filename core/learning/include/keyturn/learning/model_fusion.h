#pragma once
// Multi-view fusion with a trained model (keyturn classify --fuse): the model's pose references
// fitted on its training views, and a sequence of predicted views fused into the belief after each.
#include <string>
#include <vector>

#include "keyturn/learning/feature_table.h"
#include "keyturn/learning/model_file.h"
#include "keyturn/learning/model_predictions.h"
#include "keyturn/learning/protocols.h"
#include "keyturn/learning/view_fusion.h"

namespace keyturn::learning {

// Stores the table's rows (labelled by `kind`, as the model was trained) by azimuth in the model,
// for pose fusion. Throws keyturn::Error for a size mismatch or a row whose label is not one of
// the model's classes or whose azimuth is not finite.
void addPoseReferences(Model& model, const FeatureTable& table, const std::vector<double>& azimuth_deg,
                       LabelKind kind, double bin_deg);

// One view of a fused sequence.
struct FusedStep {
  std::size_t row = 0;        // the table row (predictRows' Prediction::row)
  double azimuth_deg = 0;
  Answer view_answer = Answer::Class;  // the view alone
  std::vector<double> belief; // after this view, one per class, summing to 1
  int best = -1;              // the belief's argmax
  Answer answer = Answer::Class;       // the fused answer (TurnFusion::answer)
};

struct ModelFusion {
  std::string method;
  std::vector<FusedStep> steps;  // one per view given
  std::size_t stopped_after = 0; // the first step whose answer is a class believed >= stop_belief (0: none)
  // Before it stopped (or in a sequence that never did): the first step whose highest belief reached
  // stop_belief with the fused answer unknown (0: none). The belief is over the model's classes; the
  // open-set rule said the object is none of them, so such a step does not stop the sequence.
  std::size_t certain_while_unknown = 0;
};

// predictions: predictRows' answers for the sequence's views, in turntable order; azimuth_deg one
// per prediction. Each view is fed to a TurnFusion (turn_fusion.h: which views count, the open-set
// rule and the stop). Throws keyturn::Error for pose fusion with a model without pose references,
// a size mismatch, or a sequence with no described view.
ModelFusion fusePredictions(const Model& model, const FeatureTable& table, const std::vector<Prediction>& predictions,
                            const std::vector<double>& azimuth_deg, const FusionOptions& options);

}  // namespace keyturn::learning
