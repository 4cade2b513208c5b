#pragma once
// One network trains or predicts at a time, whichever network it is (the MLP's or the set
// network's). Parameter initialisation draws from libtorch's global generator; and two networks
// trained on two threads at once came out different from the same network trained alone, run to
// run, even with OMP_NUM_THREADS=1 (Debian's libtorch 1.13 over its serial OpenBLAS; which shared
// state it is was not isolated): ClassifierKind.FoldsTrainedInParallelThreadsMatchSequentialOnes on
// 6,000 rows, and evaluate's figures moved by up to 0.5 points between runs. XGBoost still trains
// folds in parallel.
#include <mutex>

namespace keyturn::learning {

std::mutex& torchMutex();

}  // namespace keyturn::learning
