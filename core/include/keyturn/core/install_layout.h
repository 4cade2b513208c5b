#pragma once
// Where keyturn finds its own parts, relative to the program (or the Python module) that runs,
// so that nothing absolute is compiled in and an installed tree can move:
//   PREFIX/bin/keyturn          the programs
//   PREFIX/lib/keyturn/         plugins (plugin.h) and the simulated SR4000's libMesaSR
//   PREFIX/share/keyturn/       data: object meshes, the built-in model, the sample frame
// The build tree has the same shape (build/app/keyturn → build/lib/keyturn, build/share/keyturn,
// the latter a link to the source's data/), and so do the test programs (build/tests/…).
#include <filesystem>

namespace keyturn {

// The program or shared module this code is linked into (a Python module's own .so file).
std::filesystem::path runningFile();

// PREFIX/relative, PREFIX being the folder above the running file's folder.
std::filesystem::path prefixPath(const std::filesystem::path& relative);

// $KEYTURN_DATA_DIR if set, else PREFIX/share/keyturn; throws keyturn::Error naming the folder
// looked at when it does not exist.
std::filesystem::path dataDirectory();

}  // namespace keyturn
