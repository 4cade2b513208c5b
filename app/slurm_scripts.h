#pragma once
// keyturn slurm (docs/slurm.md): a dataset's describe and evaluate as Slurm array jobs, written
// as sbatch files and one submit.sh that chains them with --dependency=afterok. The scripts are
// keyturn command lines, the CLI's own syntax, so they are written here in app/:
//   describe.sbatch        array 1-N: describe DATASET --shard I/N (the cache's shards)
//   merge-features.sbatch  one task: describe DATASET --cache (merges them; one writer)
//   evaluate.sbatch        array 1-N: evaluate … --shard I/N (with an evaluation)
//   report.sbatch          one task: evaluate … --merge → OUT/report/
#include <string>
#include <utility>
#include <vector>

namespace keyturn::app {

struct SlurmPlan {
  std::string keyturn;          // the program the jobs run (absolute)
  std::string dataset, out;     // absolute folders; the scripts and logs go to out
  int tasks = 1;                // array size of each sharded stage
  int cpus = 1;                 // per task (--cpus-per-task; keyturn --jobs)
  std::string mem = "2G";       // per task (--mem)
  std::string time, partition;  // --time, --partition; empty: the cluster's defaults
  std::string descriptor;       // descriptor options for every stage, as shell words ("--bins 16")
  std::string evaluate;         // evaluate's options as shell words; empty: describe only
};

// {file name, text} of each script, submit.sh last. Throws keyturn::Error for a bad plan
// (tasks or cpus < 1, evaluate options the stages set themselves).
std::vector<std::pair<std::string, std::string>> slurmScripts(const SlurmPlan& plan);

// 'text' quoted for POSIX sh.
std::string shellQuote(const std::string& text);

}  // namespace keyturn::app
