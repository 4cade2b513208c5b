// keyturn import FORMAT SRC --out DATASET: another tool's dataset (Washington RGB-D, labelled folders,
// BigBIRD) as a keyturn dataset (core/dataset: dataset_import.h does the work). Files it cannot use are listed one
// a line; the rest is imported.
#include <iostream>
#include <memory>

#include "commands.h"
#include "depth_image_options.h"
#include "keyturn/core/error.h"
#include "keyturn/dataset/dataset_import.h"
#include "progress.h"

namespace keyturn::app {
namespace {

struct ImportArgs {
  dataset::ImportOptions options;
  DepthImageFlags depth;
  bool quiet = false;
};

int runImport(ImportArgs a) {
  a.options.depth = a.depth.toOptions();
  if (!a.options.categories.empty() && a.options.format != "bigbird")  // said in the flag's words before the library's
    throw Error("--categories is for bigbird (" + a.options.format + " names each view's class by its folder)");
  std::unique_ptr<Progress> bar;
  a.options.progress = [&](std::size_t done, std::size_t total) {
    if (!bar) bar = std::make_unique<Progress>("import", total, !a.quiet && total > 1);
    bar->advance();
    if (done == total) bar->finish();
  };
  const dataset::ImportReport r = dataset::importDataset(a.options);
  std::cout << r.text(a.options);
  return r.problems.empty() ? 0 : 1;
}

}  // namespace

Command addImportCommand(CLI::App& app) {
  auto a = std::make_shared<ImportArgs>();
  auto* cmd = app.add_subcommand("import", "Import another tool's dataset (washington, folders, bigbird) as a keyturn dataset");
  cmd->add_option("format", a->options.format, "washington (CATEGORY/INSTANCE/INSTANCE_VIDEO_FRAME.pcd or _depthcrop.png), folders "
                  "(CLASS/INSTANCE/[eLABEL/]VIEW.{pcd,ply,png}) or bigbird (OBJECT/NPi_ANGLE.h5, calibration.h5, poses/)")->required();
  cmd->add_option("source", a->options.source, "The dataset's folder")->required();
  cmd->add_option("--out,-o", a->options.out, "The keyturn dataset to write (new, empty, or an earlier import to resume)")->required();
  cmd->add_option("--categories", a->options.categories, "bigbird: CSV with class and instance columns, each object's class");
  cmd->add_flag("--quiet,-q", a->quiet, "No progress");
  a->depth.add(*cmd);
  return {cmd, [a] { return runImport(*a); }};
}

}  // namespace keyturn::app
