#include "../src/set_network_classifier.h"

#include <ATen/CPUGeneratorImpl.h>
#include <torch/torch.h>

#include <malloc.h>

#include <algorithm>
#include <cmath>

#include "keyturn/core/error.h"
#include "keyturn/core/plugin.h"
#include "keyturn/learning/keypoint_set.h"
#include "torch_common.h"

namespace keyturn::learning {

namespace {

constexpr int kPairInputs = 5;
constexpr double kMaxStandardised = 1e9;

// The keypoints of a batch of rows: points (B, N, 3), mask (B, N) with N = kKeypointSetSize.
struct KeypointBatch {
  torch::Tensor points, mask;
};

KeypointBatch keypointsOf(const torch::Tensor& rows) {
  const std::int64_t b = rows.size(0);
  const torch::Tensor k = rows.select(1, 0).clamp(0, kKeypointSetSize).round();
  // Bounded: no keypoint lies a kilometre away, and lengths of 1e30 would make the embeddings inf.
  const torch::Tensor points = rows.slice(1, 1, kKeypointSetWidth).reshape({b, kKeypointSetSize, 3}).clamp(-1e3, 1e3);
  const torch::Tensor index = torch::arange(kKeypointSetSize, torch::kFloat32).unsqueeze(0);
  return {points, (index < k.unsqueeze(1)).to(torch::kFloat32)};
}

struct SetNetImpl : torch::nn::Module {
  SetNetImpl(int extras, int classes, const SetNetParams& p) : dropout(p.dropout) {
    mean = register_buffer("mean", torch::zeros({extras}));
    scale = register_buffer("scale", torch::ones({extras}));
    pair1 = register_module("pair1", torch::nn::Linear(kPairInputs, p.width));
    pair2 = register_module("pair2", torch::nn::Linear(p.width, p.width));
    head1 = register_module("head1", torch::nn::Linear(2 * p.width + 2 + extras, p.hidden));
    head2 = register_module("head2", torch::nn::Linear(p.hidden, classes));
  }

  // gen set: training (dropout, and the augmentation of `augment`); null: prediction.
  torch::Tensor forward(const torch::Tensor& rows, at::Generator* gen, const SetNetParams* augment = nullptr) {
    const KeypointBatch kp = keypointsOf(rows);
    // Only the batch's largest K and each pair once (i < j): the five values are symmetric in i and j,
    // and padded keypoints are masked anyway. SR4000 views have 10–40 keypoints: most of 64² is padding.
    const std::int64_t n = std::max<std::int64_t>(2, static_cast<std::int64_t>(kp.mask.sum(1).max().item<float>()));
    torch::Tensor m = kp.mask.slice(1, 0, n);                                     // (B, n)
    torch::Tensor points = kp.points.slice(1, 0, n);
    if (gen && augment) {
      // What another view of the same object changes: some keypoints come and go, and each moves by
      // the sensor's noise.
      if (augment->keypoint_dropout > 0)
        m = m * torch::bernoulli(torch::full_like(m, 1.0 - augment->keypoint_dropout), *gen);
      if (augment->jitter_m > 0) points = points + augment->jitter_m * at::normal(0.0, 1.0, points.sizes(), *gen);
    }
    const torch::Tensor p = points * m.unsqueeze(2);
    const torch::Tensor count = m.sum(1).clamp_min(1);                            // K
    const torch::Tensor r = p.norm(2, 2);                                         // radius of each keypoint
    const torch::Tensor rms = ((r * r).sum(1) / count).sqrt().clamp_min(1e-6);    // (B)
    const torch::Tensor upper = torch::triu_indices(n, n, 1);                     // (2, n(n−1)/2)
    const torch::Tensor i = upper[0], j = upper[1];
    const torch::Tensor pi = p.index_select(1, i), pj = p.index_select(1, j);     // (B, P, 3)
    const torch::Tensor ri = r.index_select(1, i), rj = r.index_select(1, j), s = rms.unsqueeze(1);
    const torch::Tensor d = (pi - pj).norm(2, 2);
    const torch::Tensor cosine = (pi * pj).sum(2) / (ri * rj).clamp_min(1e-12);
    // Lengths in decimetres (a view spans 0.5–3 dm) and in RMS radii of the set: the first keeps an
    // instance's size, the second carries a category across sizes.
    const torch::Tensor pairs = torch::stack({d * 10, d / s, (ri + rj) / s, (ri - rj).abs() / s, cosine}, 2);
    const torch::Tensor pair_mask = (m.index_select(1, i) * m.index_select(1, j)).unsqueeze(2);  // (B, P, 1)
    const torch::Tensor e = torch::relu(pair2->forward(torch::relu(pair1->forward(pairs)))) * pair_mask;
    const torch::Tensor pooled_mean = e.sum(1) / pair_mask.sum(1).clamp_min(1);
    // Embeddings are ≥ 0 (ReLU): masked pairs at 0 never raise the max.
    const torch::Tensor pooled_max = std::get<0>(e.max(1));
    std::vector<torch::Tensor> parts = {pooled_mean, pooled_max, torch::log1p(m.sum(1)).unsqueeze(1),
                                        (rms * 10).unsqueeze(1)};
    if (mean.numel() > 0)
      parts.push_back(((rows.slice(1, kKeypointSetWidth) - mean) * scale).clamp(-kMaxStandardised, kMaxStandardised));
    torch::Tensor x = torch::relu(head1->forward(torch::cat(parts, 1)));
    if (gen && dropout > 0) x = x * torch::bernoulli(torch::full_like(x, 1.0 - dropout), *gen) / (1.0 - dropout);
    return head2->forward(x);
  }

  double dropout;
  torch::Tensor mean, scale;
  torch::nn::Linear pair1{nullptr}, pair2{nullptr}, head1{nullptr}, head2{nullptr};
};
TORCH_MODULE(SetNet);


void checkInputs(Eigen::Index cols) {
  if (cols < kKeypointSetWidth)
    throw Error("set network: " + std::to_string(cols) + " feature columns; it needs the keypoints first (features " +
                "'kpset' or 'kpset+…', " + std::to_string(kKeypointSetWidth) + " values)");
}

// The pair tensors (batch × pairs × width, 2–8 MB each) are allocated and freed a few times per
// batch. glibc gave each back to the kernel (mmap and trim thresholds), and page faults took two
// thirds of a training: 3 epochs on 1,944 views 12.5 s (8.0 s system time), 4.4 s (0.15 s) with
// the heap kept; the weights are byte for byte the same. Process-wide, once: the heap then keeps
// up to the largest batch's tensors.
void keepTheHeap() {
  static const bool once = [] {
    mallopt(M_MMAP_THRESHOLD, 1 << 30);
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
    return true;
  }();
  (void)once;
}

class SetNetworkClassifier : public Classifier {
 public:
  explicit SetNetworkClassifier(const ClassifierParams& p) : params_(p) {
    torch::set_num_threads(1);
    keepTheHeap();
  }

  void fit(const Matrix& x, const std::vector<int>& y, int classes) override {
    if (x.rows() != static_cast<Eigen::Index>(y.size()) || x.rows() == 0)
      throw Error("set network: " + std::to_string(x.rows()) + " feature rows for " + std::to_string(y.size()) +
                  " labels");
    checkInputs(x.cols());
    const SetNetParams& p = params_.setnet;
    const std::lock_guard<std::mutex> lock(torchMutex());
    torch::manual_seed(params_.seed);
    build(static_cast<int>(x.cols()), classes);
    at::Generator gen = at::make_generator<at::CPUGeneratorImpl>(params_.seed);
    const torch::Tensor inputs = toTensor(x);
    const torch::Tensor labels = torch::tensor(std::vector<std::int64_t>(y.begin(), y.end()), torch::kInt64);
    if (x.cols() > kKeypointSetWidth) {
      const torch::Tensor extra = inputs.slice(1, kKeypointSetWidth);
      net_->mean.copy_(extra.mean(0));
      net_->scale.copy_(1.0 / (extra.std(0, /*unbiased=*/false) + 1e-6));
    }
    torch::optim::Adam adam(net_->parameters(), torch::optim::AdamOptions(p.learning_rate));
    const std::int64_t n = inputs.size(0);
    // A few dozen views would see a few dozen steps in 30 epochs: at least min_steps in all.
    const std::int64_t batches = (n + p.batch - 1) / p.batch;
    const std::int64_t epochs = std::max<std::int64_t>(p.epochs, (p.min_steps + batches - 1) / batches);
    for (std::int64_t epoch = 0; epoch < epochs; ++epoch) {
      const torch::Tensor order = torch::randperm(n, gen, torch::kInt64);
      for (std::int64_t start = 0; start < n; start += p.batch) {
        const torch::Tensor idx = order.slice(0, start, std::min<std::int64_t>(n, start + p.batch));
        const torch::Tensor logits = net_->forward(inputs.index_select(0, idx), &gen, &p);
        const torch::Tensor loss = torch::nn::functional::cross_entropy(logits, labels.index_select(0, idx));
        adam.zero_grad();
        loss.backward();
        adam.step();
      }
    }
  }

  Matrix predictProba(const Matrix& x) const override {
    if (!net_) throw Error("set network: the model is not trained or loaded");
    checkInputs(x.cols());
    const std::lock_guard<std::mutex> lock(torchMutex());
    torch::NoGradGuard no_grad;
    if (x.rows() == 0) return Matrix(0, net_->head2->weight.size(0));
    const torch::Tensor all = toTensor(x);
    std::vector<torch::Tensor> out;
    // In batches: the pair tensors are K(K−1)/2 × width per view.
    for (std::int64_t start = 0; start < all.size(0); start += 256) {
      const torch::Tensor part = all.slice(0, start, std::min<std::int64_t>(all.size(0), start + 256));
      out.push_back(torch::softmax(net_->forward(part, nullptr), 1));
    }
    const torch::Tensor prob = torch::cat(out, 0).contiguous();
    return Eigen::Map<const Matrix>(prob.data_ptr<float>(), prob.size(0), prob.size(1));
  }

  void save(const std::string& path) const override {
    saveNetwork(net_, path);
  }

  void load(const std::string& path, int inputs, int classes) override {
    checkInputs(inputs);
    build(inputs, classes);
    loadNetwork(net_, path,
                "a set network of " + std::to_string(inputs) + " inputs and " + std::to_string(classes) + " classes");
    const std::int64_t got_extras = net_->mean.numel(), got_out = net_->head2->weight.size(0);
    if (got_extras != inputs - kKeypointSetWidth || got_out != classes ||
        net_->pair1->weight.size(0) != params_.setnet.width)
      throw Error(path + ": the set network takes " + std::to_string(kKeypointSetWidth + got_extras) +
                  " inputs and gives " + std::to_string(got_out) + " classes; its sidecar says " +
                  std::to_string(inputs) + " and " + std::to_string(classes));
  }

 private:
  void build(int inputs, int classes) { net_ = SetNet(inputs - kKeypointSetWidth, classes, params_.setnet); }

  ClassifierParams params_;
  mutable SetNet net_{nullptr};
};

}  // namespace

}  // namespace keyturn::learning

KEYTURN_PLUGIN_EXPORT keyturn::learning::Classifier* keyturn_setnet_make_classifier(
    const keyturn::learning::ClassifierParams& params) {
  return new keyturn::learning::SetNetworkClassifier(params);
}
