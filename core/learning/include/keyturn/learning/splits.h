#pragma once
// Train/test splits for the evaluation protocols (docs/results.md). Each fold
// lists row indices into the same feature table. Neighbouring turntable views
// are near-duplicates, so only the group-wise protocols are leakage-free.
#include <cstdint>
#include <string>
#include <vector>

namespace keyturn::learning {

struct Fold {
  std::string name;  // "fold 3", "elevation 45", "instance ycb_004_sugar_box"
  std::vector<std::size_t> train, test;
  // Open-set folds only: views of the categories left out of training, tested as unknowns.
  std::vector<std::size_t> unknown;
};

// k folds over n rows, shuffled with `seed` (the paper's protocol: k = 10, seed 7).
std::vector<Fold> kFold(std::size_t n, int k, std::uint64_t seed);

// One fold per distinct group value: test on that group, train on the rest.
std::vector<Fold> leaveOneGroupOut(const std::vector<std::string>& groups, const std::string& label);

// Category recognition: one fold per instance of every category that has two or
// more instances; that instance is tested, never trained on. Single-instance
// categories stay in training (as distractors) and get no fold.
std::vector<Fold> leaveOneInstanceOut(const std::vector<std::string>& categories,
                                      const std::vector<std::string>& instances);

// A fixed split: rows whose id is listed in `test_ids` are tested, the rest trained on.
// Throws keyturn::Error naming an id that matches no row.
Fold fixedSplit(const std::vector<std::string>& ids, const std::vector<std::string>& test_ids);

// Categories shuffled with `seed` and dealt into min(groups, categories) groups: each category's
// group (distinct_categories' order).
std::vector<int> categoryGroups(const std::vector<std::string>& distinct_categories, int groups, std::uint64_t seed);

// Open-set folds: the categories dealt into `groups` groups (categoryGroups); fold g leaves group
// g out of training entirely (its views are its unknowns) and tests the other categories' views of
// one part: elevation g mod E when the rows have E >= 2 elevations (their neighbouring turntable
// views at the same elevation are not trained on), else the g-th of `groups` shuffled parts. The
// rest of the known categories' views are trained on. Throws keyturn::Error for fewer than three
// categories (a fold must train on two) or fewer than two groups.
std::vector<Fold> openSetFolds(const std::vector<std::string>& categories, const std::vector<std::string>& elevations,
                               int groups, std::uint64_t seed);

// Open-set folds for a category model meeting both kinds of new object: fold g leaves the categories
// of group g out as unknowns (as openSetFolds) and tests, of every other category with two or more
// instances, one instance never trained on (the category's (g mod n)-th, in name order); everything
// else is trained on. Single-instance categories stay in training. Throws keyturn::Error as
// openSetFolds does, or when no category outside a group has two instances.
std::vector<Fold> openSetInstanceFolds(const std::vector<std::string>& categories,
                                       const std::vector<std::string>& instances, int groups, std::uint64_t seed);

// Nested validation inside fold i: the protocol's other folds' test views that fold i trains on,
// each tested against the rest of fold i's training views; at most max_inner of them, spread evenly
// over the other folds. Fold i's test views are in none of them. Empty when there is no other fold.
std::vector<Fold> innerFolds(const std::vector<Fold>& outer, std::size_t i, int max_inner);

}  // namespace keyturn::learning
