#pragma once
// PDFs: fixed-bin histograms normalised to sum 1.
#include <string>
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

// How a value is counted.
//  Hard: all of it in its bin — a value crossing a bin edge moves a whole count.
//  Linear: shared between the two bins whose centres it lies between, in proportion to its nearness
//    (a triangular kernel one bin wide; below the first centre or above the last, all in the end
//    bin): the PDF moves continuously as the value moves (docs/descriptors.md, "Stability").
//  Quadratic: spread over the three nearest bins by the quadratic B-spline (a kernel three bins
//    wide, with a continuous slope; what would fall outside the range goes to the end bin): the
//    PDF also changes smoothly, and a view's few values (GKPD1's K) give a less spiky PDF.
enum class Binning { Hard, Linear, Quadratic };
const char* binningName(Binning b);          // "hard", "linear", "quadratic"
Binning parseBinning(const std::string& name);  // throws keyturn::Error

// Adds one value's weight to pdf (pdf.size() bins over range).
void addToHistogram(std::vector<double>& pdf, double v, HistogramRange range, Binning binning, double weight = 1.0);

// Binning::Linear's step of addToHistogram, inline for the loops that bin millions of values
// (KPA3): bins ≥ 2 and a range of positive width, which the caller has checked.
inline void addLinearToHistogram(double* pdf, int bins, double v, HistogramRange range, double weight = 1.0) {
  // Position in bin units from the first bin's centre; bounded in double before any int.
  const double t = (v - range.lo) / (range.hi - range.lo) * bins - 0.5;
  if (!(t > 0)) {
    pdf[0] += weight;
  } else if (!(t < bins - 1)) {
    pdf[bins - 1] += weight;
  } else {
    const int b = static_cast<int>(t);
    const double f = t - b;
    pdf[b] += weight * (1.0 - f);
    pdf[b + 1] += weight * f;
  }
}

// weights, when given, one per value: each value counts with its weight (the PDF is normalised by
// the weights' sum over the finite values).
std::vector<double> histogramPdf(const std::vector<float>& values, int bins, HistogramRange range,
                                 int* clamped = nullptr, Binning binning = Binning::Hard,
                                 const std::vector<float>* weights = nullptr);

// A kernel density estimate from a PDF: pdf convolved with a Gaussian of sigma_bins bins (cut at
// 3 sigma), mass that would leave the range reflected back at its outer edges, so the sum is kept.
// A keypoint that the view's noise swaps or moves by a bin then moves mass to the bins around it
// instead of to one bin. sigma_bins 0 leaves pdf as it is (docs/descriptors.md, "Stability"). The
// chain smooths the length functions' PDFs (HistogramOptions::smoothing); the angles' stay as binned.
void smoothPdf(std::vector<double>& pdf, double sigma_bins);

}  // namespace keyturn
