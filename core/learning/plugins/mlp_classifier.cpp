#include "../src/mlp_classifier.h"

#include <ATen/CPUGeneratorImpl.h>
#include <torch/torch.h>

#include <algorithm>

#include "keyturn/core/error.h"
#include "keyturn/core/plugin.h"
#include "torch_common.h"

namespace keyturn::learning {

namespace {

constexpr double kMaxStandardised = 1e9;

// Dropout is drawn from the caller's generator, not libtorch's global one, so
// folds trained in parallel threads stay repeatable.
struct MlpNetImpl : torch::nn::Module {
  MlpNetImpl(int inputs, int classes, const MlpParams& p) : dropout(p.dropout) {
    mean = register_buffer("mean", torch::zeros({inputs}));
    scale = register_buffer("scale", torch::ones({inputs}));
    int width = inputs;
    for (int l = 0; l <= p.layers; ++l) {
      const int next = l == p.layers ? classes : p.hidden;
      layers.push_back(register_module("fc" + std::to_string(l), torch::nn::Linear(width, next)));
      width = next;
    }
  }
  torch::Tensor forward(torch::Tensor x, at::Generator* gen) {
    // Bounded: a value past ±3e38 / scale (scale is up to 1e6 for a column constant in training)
    // standardises to inf, and inf − inf in the layers to NaN probabilities. No training row comes
    // near 1e9 standard deviations.
    x = ((x - mean) * scale).clamp(-kMaxStandardised, kMaxStandardised);
    for (std::size_t l = 0; l + 1 < layers.size(); ++l) {
      x = torch::relu(layers[l]->forward(x));
      if (gen && dropout > 0)
        x = x * torch::bernoulli(torch::full_like(x, 1.0 - dropout), *gen) / (1.0 - dropout);
    }
    return layers.back()->forward(x);
  }

  double dropout;
  torch::Tensor mean, scale;
  std::vector<torch::nn::Linear> layers;
};
TORCH_MODULE(MlpNet);


class MlpClassifier : public Classifier {
 public:
  explicit MlpClassifier(const ClassifierParams& p) : params_(p) {
    // The nets are small: one thread is fastest and keeps results repeatable.
    torch::set_num_threads(1);
  }

  void fit(const Matrix& x, const std::vector<int>& y, int classes) override {
    if (x.rows() != static_cast<Eigen::Index>(y.size()) || x.rows() == 0)
      throw Error("MLP: " + std::to_string(x.rows()) + " feature rows for " + std::to_string(y.size()) + " labels");
    const MlpParams& p = params_.mlp;
    const std::lock_guard<std::mutex> lock(torchMutex());
    torch::manual_seed(params_.seed);
    build(static_cast<int>(x.cols()), classes);
    at::Generator gen = at::make_generator<at::CPUGeneratorImpl>(params_.seed);
    const torch::Tensor inputs = toTensor(x);
    const torch::Tensor labels = torch::tensor(std::vector<std::int64_t>(y.begin(), y.end()), torch::kInt64);
    net_->mean.copy_(inputs.mean(0));
    net_->scale.copy_(1.0 / (inputs.std(0, /*unbiased=*/false) + 1e-6));
    torch::optim::Adam adam(net_->parameters(), torch::optim::AdamOptions(p.learning_rate));
    const std::int64_t n = inputs.size(0);
    const torch::Tensor one_hot = torch::one_hot(labels, classes).to(torch::kFloat32);
    for (int epoch = 0; epoch < p.epochs; ++epoch) {
      const torch::Tensor order = torch::randperm(n, gen, torch::kInt64);
      for (std::int64_t start = 0; start < n; start += p.batch) {
        const torch::Tensor idx = order.slice(0, start, std::min<std::int64_t>(n, start + p.batch));
        const torch::Tensor out = net_->forward(inputs.index_select(0, idx), &gen);
        const torch::Tensor loss =
            p.sigmoid_output
                ? torch::binary_cross_entropy_with_logits(out, one_hot.index_select(0, idx))
                : torch::nn::functional::cross_entropy(out, labels.index_select(0, idx));
        adam.zero_grad();
        loss.backward();
        adam.step();
      }
    }
  }

  Matrix predictProba(const Matrix& x) const override {
    if (!net_) throw Error("MLP: the model is not trained or loaded");
    const std::lock_guard<std::mutex> lock(torchMutex());
    torch::NoGradGuard no_grad;
    const torch::Tensor logits = net_->forward(toTensor(x), nullptr);
    torch::Tensor prob = params_.mlp.sigmoid_output ? torch::sigmoid(logits) : torch::softmax(logits, 1);
    if (params_.mlp.sigmoid_output) {
      // Every class's sigmoid can round to 0 (all logits below about -104): then 0 / 0. Such a
      // row's shares come from the logs instead (the same ratio, without the underflow).
      const torch::Tensor sum = prob.sum(1, true);
      prob = torch::where(sum > 0, prob / sum, torch::softmax(torch::log_sigmoid(logits), 1));
    }
    prob = prob.contiguous();
    return Eigen::Map<const Matrix>(prob.data_ptr<float>(), prob.size(0), prob.size(1));
  }

  void save(const std::string& path) const override {
    saveNetwork(net_, path);
  }

  void load(const std::string& path, int inputs, int classes) override {
    build(inputs, classes);
    loadNetwork(net_, path,
                "a network of " + std::to_string(inputs) + " inputs and " + std::to_string(classes) + " classes");
    // libtorch replaces each tensor wholesale on load: check the shapes it brought.
    const auto params = net_->parameters();
    const std::int64_t got_in = net_->mean.numel(), got_out = params.back().size(0);
    if (got_in != inputs || got_out != classes || params.front().size(1) != inputs)
      throw Error(path + ": the network takes " + std::to_string(params.front().size(1)) + " inputs and gives " +
                  std::to_string(got_out) + " classes; its sidecar says " + std::to_string(inputs) + " and " +
                  std::to_string(classes));
  }

 private:
  void build(int inputs, int classes) { net_ = MlpNet(inputs, classes, params_.mlp); }

  ClassifierParams params_;
  mutable MlpNet net_{nullptr};  // forward() is not const in libtorch
};

}  // namespace

}  // namespace keyturn::learning

KEYTURN_PLUGIN_EXPORT keyturn::learning::Classifier* keyturn_mlp_make_classifier(
    const keyturn::learning::ClassifierParams& params) {
  return new keyturn::learning::MlpClassifier(params);
}
