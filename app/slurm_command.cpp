// keyturn slurm: writes a dataset's describe (and evaluate) as Slurm array jobs — sbatch files
// and a submit.sh chaining them — for a cluster (slurm_scripts.h; docs/slurm.md).
#include <sys/stat.h>

#include <filesystem>
#include <iostream>

#include "commands.h"
#include "keyturn/core/durable_file.h"
#include "keyturn/core/error.h"
#include "slurm_scripts.h"
#include "keyturn/dataset/dataset_layout.h"
#include "keyturn/dataset/dataset_views.h"

namespace keyturn::app {
namespace {

namespace fs = std::filesystem;

int runSlurm(SlurmPlan p) {
  if (!dataset::isDataset(p.dataset))
    throw Error(p.dataset + ": not a dataset folder (no " + dataset::kManifestFile + ")");
  p.keyturn = fs::canonical("/proc/self/exe").string();
  p.dataset = fs::absolute(p.dataset).lexically_normal().string();
  p.out = fs::absolute(p.out).lexically_normal().string();
  for (const auto& [name, text] : slurmScripts(p)) {
    const std::string path = (fs::path(p.out) / name).string();
    writeFileDurably(path, text);
    ::chmod(path.c_str(), 0755);
  }
  std::cout << "bash " << shellQuote((fs::path(p.out) / "submit.sh").string()) << "\n";
  return 0;
}

}  // namespace

Command addSlurmCommand(CLI::App& app) {
  auto p = std::make_shared<SlurmPlan>();
  auto* cmd = app.add_subcommand(
      "slurm", "Write a dataset's describe and evaluate as Slurm array jobs: sbatch files and submit.sh (docs/slurm.md)");
  cmd->add_option("dataset", p->dataset, "Dataset folder (manifest.csv)")->required();
  cmd->add_option("--tasks,-n", p->tasks, "Array tasks per sharded stage")->required()->check(CLI::PositiveNumber);
  cmd->add_option("--out,-o", p->out, "Folder for the scripts, the logs and the report (OUT/report/)")->required();
  cmd->add_option("--evaluate", p->evaluate,
                  "evaluate's options as shell words, e.g. \"--features 'kpd2 esf' --protocol kfold10\"; "
                  "without it, describe only")
      ->allow_extra_args(false);
  cmd->add_option("--descriptor", p->descriptor, "Descriptor options for every stage as shell words, e.g. \"--bins 16\"");
  cmd->add_option("--cpus", p->cpus, "CPUs per task (--cpus-per-task; keyturn's --jobs)")->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--mem", p->mem, "Memory per task (sbatch --mem)")->capture_default_str();
  cmd->add_option("--time", p->time, "Time limit per task (sbatch --time); default: the partition's");
  cmd->add_option("--partition", p->partition, "Partition (sbatch --partition); default: the cluster's");
  return {cmd, [p] { return runSlurm(*p); }};
}

}  // namespace keyturn::app
