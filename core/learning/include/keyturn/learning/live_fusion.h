#pragma once
// One object's live views fused as the turntable turns it (the studio's fused belief beside the
// single view's): each view's answer, class probabilities and features arrive with the table's
// angle; one view stands for each azimuth bin (the pose references' bin, 5°), so a table at rest
// does not count one view many times over. While the table stays in the sequence's newest bin, the
// newest frame stands for it: a first frame taken as the object was set down (or a noisy one)
// does not hold the answer until the table turns. A bin the table has left is not taken again.
// Pose fusion when the
// model holds pose references, else independent. The turn's counts, belief and answer are a
// TurnFusion's (turn_fusion.h), as for classify --fuse and evaluate's turns.
#include <string>
#include <vector>

#include "keyturn/learning/model_file.h"
#include "keyturn/learning/open_set.h"
#include "keyturn/learning/turn_fusion.h"
#include "keyturn/learning/view_fusion.h"

namespace keyturn::learning {

class LiveFusion {
 public:
  LiveFusion() = default;  // no model: nothing is fused
  explicit LiveFusion(const ModelInfo& model, FusionOptions options = {});

  const std::string& method() const { return options_.method; }
  // False when the view is not taken: no model, "no object", no finite angle, a bin the table has
  // left, or probabilities (features, for the pose term) that are not one per class (the
  // classifier's input). A view in the newest bin replaces that bin's view. score: the view's
  // open-set score (Recognition::score).
  bool add(Answer answer, double score, const std::vector<float>& probabilities, const std::vector<float>& features,
           double azimuth_deg);
  void reset();  // a new object, or a new turn

  std::size_t views() const { return turn_.views(); }  // taken, "unknown" ones included
  std::size_t unknownViews() const { return turn_.unknownViews(); }
  double turnedDeg() const { return turned_deg_; }     // summed turn between the views taken
  std::vector<double> belief() const { return turn_.belief(); }  // over the classes; empty before any evidence
  int best() const { return turn_.best(); }                      // -1 before any evidence
  Answer answer() const { return turn_.answer(); }               // NoObject before any view

 private:
  std::vector<std::string> classes_;
  PoseReferences references_;
  OpenSet open_set_;  // its method and threshold (the references stay in the model)
  FusionOptions options_;
  struct Taken {
    int bin = 0;
    double azimuth_deg = 0;
  };

  std::vector<Taken> taken_;  // one per bin, in the order the table reached them
  TurnFusion turn_{FusionOptions{}, OpenSet{}};
  double turned_deg_ = 0;
  // The same before the newest view, which a frame in its bin replaces.
  TurnFusion before_newest_{FusionOptions{}, OpenSet{}};
  double turned_before_newest_ = 0;
};

}  // namespace keyturn::learning
