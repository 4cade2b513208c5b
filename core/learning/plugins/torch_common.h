#pragma once
// What the two networks (the MLP, the set network) share: one lock, the feature matrix as a tensor,
// and their files.
//
// One network trains or predicts at a time, whichever network it is (the MLP's or the set
// network's). Parameter initialisation draws from libtorch's global generator; and two networks
// trained on two threads at once came out different from the same network trained alone, run to
// run, even with OMP_NUM_THREADS=1 (Debian's libtorch 1.13 over its serial OpenBLAS; which shared
// state it is was not isolated): ClassifierKind.FoldsTrainedInParallelThreadsMatchSequentialOnes on
// 6,000 rows, and evaluate's figures moved by up to 0.5 points between runs. XGBoost still trains
// folds in parallel.
#include <torch/torch.h>

#include <mutex>
#include <string>

#include "keyturn/core/error.h"
#include "keyturn/learning/classifier.h"

namespace keyturn::learning {

std::mutex& torchMutex();

// Missing values (NaN: a block a view could not give) enter a network as 0, and so do ±inf
// (no feature is infinite; nan_to_num's default made them ±3.4e38, then NaN probabilities).
torch::Tensor toTensor(const Matrix& x);

template <class Net>
void saveNetwork(const Net& net, const std::string& path) {
  try {
    torch::save(net, path);
  } catch (const c10::Error& e) {
    throw Error(path + ": cannot write the network: " + e.what_without_backtrace());
  }
}

// `what`: the network the sidecar describes ("a network of 64 inputs and 15 classes"), for the error.
template <class Net>
void loadNetwork(Net& net, const std::string& path, const std::string& what) {
  try {
    torch::load(net, path);
  } catch (const c10::Error& e) {
    throw Error(path + ": not " + what + " as its sidecar says (" +
                std::string(e.what_without_backtrace()).substr(0, 160) + ")");
  }
}

}  // namespace keyturn::learning
