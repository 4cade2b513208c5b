#include "slurm_scripts.h"

#include <sstream>

#include "keyturn/core/error.h"

namespace keyturn::app {
namespace {

// Options the stages set themselves; given in --evaluate they would fight them.
const char* const kStageOptions[] = {"--out", "-o", "--shard", "--merge", "--jobs", "-j", "--json"};

bool hasWord(const std::string& words, const std::string& option) {
  std::istringstream in(words);
  std::string w;
  while (in >> w)
    if (w == option || w.rfind(option + "=", 0) == 0) return true;
  return false;
}

// An sbatch file: its #SBATCH lines, then the command (one line, exec'd: the task's exit code is keyturn's).
std::string sbatch(const SlurmPlan& p, const std::string& name, bool array, const std::string& command) {
  std::ostringstream s;
  s << "#!/bin/sh\n"
    << "# Written by keyturn slurm; submit with submit.sh (it chains the stages).\n"
    << "#SBATCH --job-name=keyturn-" << name << "\n";
  if (array) s << "#SBATCH --array=1-" << p.tasks << "\n";
  s << "#SBATCH --cpus-per-task=" << p.cpus << "\n"
    << "#SBATCH --mem=" << p.mem << "\n";
  if (!p.time.empty()) s << "#SBATCH --time=" << p.time << "\n";
  if (!p.partition.empty()) s << "#SBATCH --partition=" << p.partition << "\n";
  s << "#SBATCH --chdir=" << p.out << "\n"
    << "#SBATCH --output=" << p.out << "/logs/" << name << (array ? "-%a" : "") << ".out\n"
    << "exec " << command << "\n";
  return s.str();
}

}  // namespace

std::string shellQuote(const std::string& text) {
  std::string q = "'";
  for (char c : text) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::vector<std::pair<std::string, std::string>> slurmScripts(const SlurmPlan& p) {
  if (p.tasks < 1) throw Error("--tasks must be at least 1, not " + std::to_string(p.tasks));
  if (p.cpus < 1) throw Error("--cpus must be at least 1, not " + std::to_string(p.cpus));
  for (const char* o : kStageOptions)
    if (hasWord(p.evaluate, o))
      throw Error(std::string("--evaluate: leave out ") + o + " (the stages set --out, --shard, --merge and --jobs)");
  const std::string n = std::to_string(p.tasks), kt = shellQuote(p.keyturn), ds = shellQuote(p.dataset);
  const std::string jobs = " --jobs \"${SLURM_CPUS_PER_TASK:-" + std::to_string(p.cpus) + "}\"";
  const std::string desc = p.descriptor.empty() ? "" : " " + p.descriptor;
  const std::string report = shellQuote(p.out + "/report");
  std::vector<std::pair<std::string, std::string>> files;
  files.push_back({"describe.sbatch", sbatch(p, "describe", true,
                                             kt + " describe " + ds + " --shard \"${SLURM_ARRAY_TASK_ID}/" + n + "\"" +
                                                 jobs + desc + " -q")});
  files.push_back({"merge-features.sbatch", sbatch(p, "merge-features", false, kt + " describe " + ds + " --cache" + jobs + desc + " -q")});
  const bool evaluate = !p.evaluate.empty();
  if (evaluate) {
    const std::string args = " " + p.evaluate + desc + " --out " + report;
    files.push_back({"evaluate.sbatch", sbatch(p, "evaluate", true,
                                               kt + " evaluate " + ds + args + " --shard \"${SLURM_ARRAY_TASK_ID}/" + n +
                                                   "\"" + jobs + " -q")});
    files.push_back({"report.sbatch", sbatch(p, "report", false, kt + " evaluate " + ds + args + " --merge" + jobs + " -q")});
  }
  std::ostringstream s;
  s << "#!/bin/sh\n"
    << "# Submits keyturn's stages, each after the one before has ended well (--dependency=afterok),\n"
    << "# and prints the job ids, the last one's last. Extra arguments go to every sbatch.\n"
    << "set -e\n"
    << "cd " << shellQuote(p.out) << "\n"
    << "mkdir -p logs\n"
    << "submit() { id=$(sbatch --parsable \"$@\"); echo \"${id%%;*}\"; }\n"
    << "describe=$(submit \"$@\" describe.sbatch)\n"
    << "merge=$(submit \"$@\" --dependency=afterok:$describe merge-features.sbatch)\n";
  if (evaluate)
    s << "evaluate=$(submit \"$@\" --dependency=afterok:$merge evaluate.sbatch)\n"
      << "report=$(submit \"$@\" --dependency=afterok:$evaluate report.sbatch)\n"
      << "echo \"$describe $merge $evaluate $report\"\n";
  else
    s << "echo \"$describe $merge\"\n";
  files.push_back({"submit.sh", s.str()});
  return files;
}

}  // namespace keyturn::app
