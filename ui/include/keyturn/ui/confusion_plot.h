#pragma once
// A confusion matrix as a PNG heat map (rows: true class, columns: predicted),
// each cell shaded by the share of its row and labelled with its count.
#include <string>
#include <vector>

namespace keyturn::ui {

struct ConfusionMatrix {
  std::string title;
  std::vector<std::string> labels;
  std::vector<std::vector<int>> counts;  // [true][predicted]
};

// Throws keyturn::Error naming the file when it cannot be written.
void saveConfusionPng(const ConfusionMatrix& matrix, const std::string& path);

}  // namespace keyturn::ui
