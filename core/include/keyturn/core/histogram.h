#pragma once
// PDFs: fixed-bin histograms normalised to sum 1.
#include <vector>

namespace keyturn {

struct HistogramRange {
  double lo = 0.0;
  double hi = 1.0;
};

// Values outside [lo, hi] are clamped into the first/last bin so no sample is
// lost; NaN and infinite values are ignored. All-empty input gives all zeros.
// The bin of a finite value: floor((v − lo) / (hi − lo) · bins), clamped into [0, bins).
int histogramBin(double v, int bins, HistogramRange range);
std::vector<double> histogramPdf(const std::vector<float>& values, int bins, HistogramRange range,
                                 int* clamped = nullptr);

}  // namespace keyturn
