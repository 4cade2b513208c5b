#pragma once
// Dissimilarities between two PDFs of equal length (each summing to 1).
#include <string>
#include <vector>

namespace keyturn {

enum class Dissimilarity { Bhattacharyya, ChiSquared, L1, JensenShannon, Emd };

// Bhattacharyya: -ln Σ sqrt(p q), capped at 50 for disjoint PDFs (the paper's Fig 16).
double bhattacharyya(const std::vector<double>& p, const std::vector<double>& q);
// χ²: ½ Σ (p-q)²/(p+q), bins where both are 0 skipped; in [0, 1].
double chiSquared(const std::vector<double>& p, const std::vector<double>& q);
// L1: Σ |p-q|; in [0, 2].
double l1Distance(const std::vector<double>& p, const std::vector<double>& q);
// Jensen–Shannon divergence in nats; in [0, ln 2].
double jensenShannon(const std::vector<double>& p, const std::vector<double>& q);
// 1-D earth mover's distance Σ|CDF_p - CDF_q| / bins: the mass-weighted shift as
// a fraction of the histogram range; in [0, 1].
double emd1d(const std::vector<double>& p, const std::vector<double>& q);

double dissimilarity(Dissimilarity d, const std::vector<double>& p, const std::vector<double>& q);
Dissimilarity parseDissimilarity(const std::string& name);  // throws keyturn::Error

}  // namespace keyturn
