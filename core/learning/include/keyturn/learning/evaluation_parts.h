#pragma once
// keyturn evaluate as array jobs (docs/slurm.md): each shard's trainings (foldJobs) are
// written as a part, OUT/parts/part-I-of-N.json, and a complete set of parts is merged back
// into the run, which then reports as a single run does: the same accuracies, folds and
// confusion matrices; only the wall times (seconds, train and predict ms per view) are the
// parts' own.
#include <string>

#include "keyturn/learning/evaluation_report.h"

namespace keyturn::learning {

// OUT/parts/part-I-of-N.json (shard counts from 0).
std::string evaluationPartPath(const std::string& out, int shard, int shards);
// The shard's fold outcomes (evaluateRows(run, …, shard, shards) has run) and the plan they belong to.
std::string evaluationPartJson(const EvaluationRun& run, int shard, int shards);
// Fills every row of a prepared run from the one complete set of parts in OUT/parts/ and
// returns its N. Throws keyturn::Error naming the folder or file: no parts, parts missing,
// two complete sets, a part that is not valid or was made by another plan (feature sets,
// classifiers, protocols, bins, seeds, classifier or descriptor parameters, views).
int mergeEvaluationParts(EvaluationRun& run, const std::string& out);

}  // namespace keyturn::learning
