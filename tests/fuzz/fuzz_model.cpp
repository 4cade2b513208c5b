// A trained model meeting a view, as `keyturn classify` (predictRows over rows described for the
// model), the Python module's Model.classify and live recognition (Recognizer::recognize) apply
// it: rows of degenerate features (K < 3, all-zero PDFs, NaN, inf, huge, denormal, raw bits) or a
// degenerate cloud described with the model's own parameters. Three models: the built-in XGBoost
// one, and a small network trained here at start with a softmax and with a sigmoid output. Only
// keyturn::Error may come out; every prediction names a class and gives finite probabilities
// summing to 1.
#include <cstdio>
#include <cstdlib>
#include <memory>

#include "chain_input.h"
#include "keyturn/learning/feature_cache.h"
#include "keyturn/learning/model_predictions.h"
#include "keyturn/learning/model_training.h"
#include "keyturn/learning/recognizer.h"

namespace kl = keyturn::learning;

namespace {

void check(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "fuzz_model: %s\n", what);
  std::abort();
}

void checkProbabilities(const std::vector<float>& p, int best, std::size_t classes) {
  std::string shown;
  for (float v : p) shown += " " + std::to_string(v);
  const auto check = [&](bool ok, const char* what) {
    if (ok) return;
    std::fprintf(stderr, "fuzz_model: %s (best %d, probabilities%s)\n", what, best, shown.c_str());
    std::abort();
  };
  check(p.size() == classes, "probabilities for another number of classes");
  check(best >= 0 && static_cast<std::size_t>(best) < classes, "a best class out of range");
  double sum = 0;
  for (float v : p) {
    check(std::isfinite(v) && v >= 0.f && v <= 1.f + 1e-5f, "a probability outside [0, 1]");
    sum += v;
  }
  check(std::abs(sum - 1.0) < 1e-3, "probabilities not summing to 1");
}

// A network trained on a few synthetic rows of the built-in model's layout.
kl::Model smallNetwork(const kl::Model& like, bool sigmoid) {
  kl::FeatureTable t = kl::modelLayout(like, "fuzz");
  std::uint32_t rng = 12345;
  for (int r = 0; r < 12; ++r) {
    kl::FeatureRow row;
    row.id = "v" + std::to_string(r);
    row.cls = "c" + std::to_string(r % 3);
    row.instance = row.cls + "_1";
    row.elevation = "30";
    row.keypoints = 20;
    for (int k = 0; k < t.width(); ++k) {
      rng = rng * 1664525u + 1013904223u;
      row.values.push_back(static_cast<float>((rng >> 8) / 16777216.0 / t.width()) + (k % 3 == r % 3 ? 0.05f : 0.f));
    }
    t.rows.push_back(row);
  }
  kl::ClassifierParams p;
  p.kind = "mlp";
  p.mlp.hidden = 16;
  p.mlp.epochs = 3;
  p.mlp.sigmoid_output = sigmoid;
  return kl::trainModel(t, like.info.blocks, kl::LabelKind::Category, p);
}

struct Models {
  std::vector<kl::Model> models;
  std::vector<std::unique_ptr<kl::Recognizer>> recognizers;
  Models() {
    const std::string dir = std::string(KEYTURN_DATA_DIR) + "/models/sim-objects";
    models.push_back(kl::loadModel(dir));
    recognizers.push_back(std::make_unique<kl::Recognizer>(kl::Recognizer::load(dir)));
    for (bool sigmoid : {false, true}) {
      models.push_back(smallNetwork(models.front(), sigmoid));
      recognizers.push_back(std::make_unique<kl::Recognizer>(smallNetwork(models.front(), sigmoid), "fuzz"));
    }
  }
};

float featureValue(keyturn::fuzz::Bytes& in, std::uint8_t pattern, int k, int width) {
  switch (pattern % 9) {
    case 0: return 0.f;                                           // all-zero PDF
    case 1: return std::nanf("");                                 // missing
    case 2: return k == 0 ? 1.f : 0.f;                            // a spike
    case 3: return 1.f / static_cast<float>(width);               // uniform
    case 4: return std::numeric_limits<float>::infinity() * (k % 2 ? 1 : -1);
    case 5: return std::numeric_limits<float>::max() * (k % 2 ? 1 : -1);
    case 6: return std::numeric_limits<float>::denorm_min();
    case 7: return static_cast<float>(in.power(-40, 38));
    default: return in.rawFloat();
  }
}

// Never destroyed: libtorch and XGBoost may be gone at exit.
Models* models = nullptr;

}  // namespace

// The models are made before the first input: loading libtorch and training two networks under
// ASan took over libFuzzer's 20 s per input on a loaded machine (a 5-minute run stopped on the
// empty input with "timeout", inside libtorch's start-up), a cost of the harness, not of an input.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  models = new Models;
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Models& m = *models;
  if (size < 2) return 0;
  keyturn::fuzz::Bytes in(data, size);
  const std::uint8_t mode = in.u8();
  const std::size_t which = mode % 3;
  const kl::Model& model = m.models[which];
  const std::size_t classes = model.info.classes.size();
  try {
    if (mode & 0x80) {  // a degenerate cloud, described with the model's parameters
      const keyturn::Cloud cloud = keyturn::fuzz::decodeCloud(in, mode & 0x40);
      if (mode & 0x20) {
        const kl::Recognition r = m.recognizers[which]->recognize(cloud);
        checkProbabilities(r.probabilities, r.best, classes);
      } else {
        kl::FeatureTable t = kl::modelLayout(model, "fuzz");
        t.rows.push_back(kl::describeCloud(cloud, kl::modelOptions(model, "fuzz"), t));
        for (const auto& p : kl::predictRows(model, t, "fuzz"))
          if (p.answer != kl::Answer::NoObject) checkProbabilities(p.probabilities, p.best, classes);
      }
      return 0;
    }
    kl::FeatureTable t = kl::modelLayout(model, "fuzz");  // rows as classify builds them
    const int rows = 1 + in.u8() % 6;
    for (int r = 0; r < rows; ++r) {
      kl::FeatureRow row;
      row.id = "v" + std::to_string(r);
      row.keypoints = static_cast<int>(in.u8()) - 2;  // -2 … 253: none, K < 3, any
      if (in.u8() & 1) row.problem = "too few keypoints";
      for (int b = 0; b < static_cast<int>(t.blocks.size()); ++b) {
        const std::uint8_t pattern = in.u8();
        for (int k = 0; k < t.sizes[b]; ++k) row.values.push_back(featureValue(in, pattern, k, t.sizes[b]));
      }
      t.rows.push_back(row);
    }
    const auto predictions = kl::predictRows(model, t, "fuzz");
    for (const auto& p : predictions) {
      check(p.row < t.rows.size(), "a prediction for a row that is not there");
      check(p.answer != kl::Answer::NoObject, "no object for a row that was not described as empty");
      checkProbabilities(p.probabilities, p.best, classes);
    }
  } catch (const keyturn::Error&) {
  }
  return 0;
}
