#pragma once
// OpenMP threads that sleep while they wait (docs/benchmarks.md, "OpenMP threads that wait passively").
namespace keyturn::app {

// libgomp (loaded at start with XGBoost and PCL, used by Open3D's reconstruction) reads
// OMP_WAIT_POLICY once, when it is loaded, and by default an idle team thread spins for about 3 ms
// after each parallel region. Open3D runs thousands of short regions, so beside the program's other
// threads (the studio's camera and recognition) or other work on the machine the spinning took the
// core the work needed: `keyturn reconstruct` of 8 views took 29.1 s at load 6, 10.0 s passive.
// When the user has not chosen a policy, sets PASSIVE and executes the program again (same PID,
// arguments and environment otherwise), the only way to reach libgomp before it reads it: glibc
// restores the environment after an executable's .preinit_array runs. A failed exec is ignored.
// Costs a second start (88 ms for `keyturn --version`, 0.104 → 0.192 s).
void waitPassivelyInOpenMp(char** argv);

}  // namespace keyturn::app
