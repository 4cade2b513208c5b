#include "torch_common.h"

namespace keyturn::learning {

std::mutex& torchMutex() {
  static std::mutex m;
  return m;
}

torch::Tensor toTensor(const Matrix& x) {
  return torch::nan_to_num(torch::from_blob(const_cast<float*>(x.data()), {x.rows(), x.cols()}, torch::kFloat32), 0.0,
                           0.0, 0.0)
      .clone();
}

}  // namespace keyturn::learning
