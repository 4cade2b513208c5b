#include "keyturn/core/dissimilarity.h"

#include <algorithm>
#include <cmath>

#include "keyturn/core/error.h"

namespace keyturn {
namespace {
void requireSameSize(const std::vector<double>& p, const std::vector<double>& q) {
  if (p.size() != q.size() || p.empty())
    throw Error("dissimilarity: PDFs have different or zero lengths (" + std::to_string(p.size()) +
                " vs " + std::to_string(q.size()) + ")");
}
}  // namespace

double bhattacharyya(const std::vector<double>& p, const std::vector<double>& q) {
  requireSameSize(p, q);
  double bc = 0.0, mass_p = 0.0, mass_q = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    bc += std::sqrt(std::max(0.0, p[i] * q[i]));
    mass_p += p[i];
    mass_q += q[i];
  }
  // Over the PDFs' own mass (float PDFs sum to 1 only within ~1e-8): a PDF is then exactly 0
  // from itself, as sqrt(p·p) is exactly p.
  if (mass_p > 0 && mass_q > 0) bc /= std::sqrt(mass_p * mass_q);
  return bc <= std::exp(-50.0) ? 50.0 : std::max(0.0, -std::log(bc));
}

double chiSquared(const std::vector<double>& p, const std::vector<double>& q) {
  requireSameSize(p, q);
  double s = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double sum = p[i] + q[i];
    if (sum > 0) s += (p[i] - q[i]) * (p[i] - q[i]) / sum;
  }
  return 0.5 * s;
}

double l1Distance(const std::vector<double>& p, const std::vector<double>& q) {
  requireSameSize(p, q);
  double s = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) s += std::abs(p[i] - q[i]);
  return s;
}

double jensenShannon(const std::vector<double>& p, const std::vector<double>& q) {
  requireSameSize(p, q);
  double s = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double m = 0.5 * (p[i] + q[i]);
    if (p[i] > 0) s += 0.5 * p[i] * std::log(p[i] / m);
    if (q[i] > 0) s += 0.5 * q[i] * std::log(q[i] / m);
  }
  return std::max(0.0, s);
}

double emd1d(const std::vector<double>& p, const std::vector<double>& q) {
  requireSameSize(p, q);
  double cp = 0.0, cq = 0.0, s = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    cp += p[i];
    cq += q[i];
    s += std::abs(cp - cq);
  }
  return s / static_cast<double>(p.size());
}

double dissimilarity(Dissimilarity d, const std::vector<double>& p, const std::vector<double>& q) {
  switch (d) {
    case Dissimilarity::Bhattacharyya: return bhattacharyya(p, q);
    case Dissimilarity::ChiSquared: return chiSquared(p, q);
    case Dissimilarity::L1: return l1Distance(p, q);
    case Dissimilarity::JensenShannon: return jensenShannon(p, q);
    case Dissimilarity::Emd: return emd1d(p, q);
  }
  return 0.0;
}

Dissimilarity parseDissimilarity(const std::string& name) {
  if (name == "bhattacharyya") return Dissimilarity::Bhattacharyya;
  if (name == "chi2" || name == "chisquared") return Dissimilarity::ChiSquared;
  if (name == "l1") return Dissimilarity::L1;
  if (name == "js" || name == "jensen-shannon") return Dissimilarity::JensenShannon;
  if (name == "emd") return Dissimilarity::Emd;
  throw Error("unknown dissimilarity '" + name + "' (expected bhattacharyya, chi2, l1, js, emd)");
}

}  // namespace keyturn
