// huygens: run a scene without graphics, or validate the physics against analytic solutions.
//   huygens run SCENE [--steps N] [--dump DIR] [--dump-every K] [--dump-format npy|vtk|both] [--overwrite]
//                     [--stats-json FILE] [--fast-plans] [--no-fsync]
//   huygens validate [CASE...] [--list] [--jobs N]
// Exit codes (program.hpp, README): 0 ok, 1 a validation case failed or a write failed, 2 bad
// scene or usage, 3 a non-finite value (or a negative LBM depth), 4 not enough memory, 130/143 stopped
// by SIGINT/SIGTERM.
#include <cstdio>
#include <string>

#include "commands.hpp"
#include "huygens/common/comm.hpp"
#include "huygens/common/program.hpp"
#include "huygens/common/shipped_scenes.hpp"

namespace huygens {

namespace {
const char* const kUsage =
    "usage: huygens run SCENE [--steps N] [--dump DIR] [--dump-every K] [--dump-format npy|vtk|both]\n"
    "                         [--overwrite] [--stats-json FILE] [--fast-plans] [--no-fsync]\n"
    "       huygens run SCENE --dry-run [--ranks P] [--rank-memory GIB]\n"
    "       mpirun -np P huygens run SCENE ...   (MPI build: P ranks, docs/scale.md)\n"
    "       huygens validate [CASE...] [--list] [--jobs N]\n"
    "       huygens --help\n"
    "\n"
    "run       runs SCENE without graphics for N full steps (default 100). SCENE is a JSON scene\n"
    "          file or, when no such file exists, a shipped scene by name (\"ocean\" or \"ocean.json\"):\n"
    "          %s.\n"
    "          It prints the per-stage timing table, and with --dump writes DIR/<field>_NNNNNN.npy\n"
    "          (float32, C order, metres) every K steps (default 1) plus DIR/meta.json. With\n"
    "          time.display_per_step = D > 1 it also writes the D - 1 displayed frames\n"
    "          interpolated inside the step before each dumped step as <field>_NNNNNN_J.npy\n"
    "          (NNNNNN = the step they follow, J = 1..D-1, time (NNNNNN + J/D) dt); meta.json\n"
    "          marks them \"interpolated\": true with \"s\": J/D. --dump-format vtk (or both: vtk\n"
    "          and npy; default npy) writes VTK XML files for ParaView instead: the grid fields\n"
    "          as DIR/grid_NNNNNN[_J].vti (image data, spacing and origin in metres), SPH\n"
    "          particles as DIR/particles_NNNNNN.vtu (pos as points; vel, density, pressure),\n"
    "          and DIR/run.pvd, the time series ParaView opens (one process only, not under\n"
    "          mpirun). A DIR that holds another run's files (meta.json, run.pvd,\n"
    "          <field>_NNNNNN*.npy|vti|vtu) is refused; --overwrite removes those\n"
    "          files first and leaves every other file in DIR. Each dump is flushed to the disk\n"
    "          (fsync of each file, then of DIR) before meta.json lists it, so the files\n"
    "          meta.json lists survive a power cut; --no-fsync skips the flushes (scratch runs:\n"
    "          a crash of the machine may then lose listed files; docs/robustness.md).\n"
    "          --stats-json FILE writes the stage table as JSON. --fast-plans plans FFTs with\n"
    "          FFTW_ESTIMATE instead of FFTW_MEASURE: a quicker start, transforms 1.4-1.9x\n"
    "          slower, and the same bits on every run (FFTW_MEASURE picks its plan by timing,\n"
    "          so two runs may differ in the last bits; docs/performance.md); under mpirun the\n"
    "          Huygens spectrum is then the one-process run's bit for bit (docs/scale.md).\n"
    "          The scene is refused before the run when it needs more memory than is available\n"
    "          (HUYGENS_MAX_MEMORY_GIB lowers the limit). SIGINT/SIGTERM stop the run after the\n"
    "          current step: meta.json records \"stopped\", the stage table is printed.\n"
    "          --dry-run prints the memory the scene needs per rank on P ranks (--ranks P,\n"
    "          default the ranks of this run) and for P = 1, 2, 4 ... 256, and from which P it\n"
    "          fits in GIB per rank (--rank-memory; default: what this machine has), then\n"
    "          exits 0 without running. Under mpirun (an MPI build) the scene runs on P\n"
    "          ranks: LBM dumps are bitwise those of one process; rank 0 prints and writes\n"
    "          meta.json, the .npy files are written by all ranks (MPI-IO).\n"
    "validate  runs the analytic validation cases (all, or the named ones) and prints\n"
    "          case, quantity, measured, expected, error, tolerance, pass/fail.\n"
    "          --list prints the case names; --jobs N runs N cases at once (each with its\n"
    "          share of the OpenMP threads; the table keeps its order).\n"
    "\n"
    "exit codes: 0 ok; 1 a case failed or a write failed; 2 bad scene or usage; 3 non-finite\n"
    "            value (or a negative LBM depth); 4 not enough memory; 130/143 stopped by\n"
    "            SIGINT/SIGTERM.\n";

// the shipped scenes' names, wrapped to the usage text's width and indent
std::string scene_list() {
  std::string out, word;
  std::size_t line = 10;
  for (const char* c = shipped_scene_names();; ++c) {
    if (*c != ' ' && *c != '\0') {
      word += *c;
      continue;
    }
    if (line + word.size() + 1 > 100) out += "\n          ", line = 10;
    out += (line > 10 ? " " : "") + word;
    line += word.size() + (line > 10 ? 1 : 0);
    word.clear();
    if (*c == '\0') return out;
  }
}
}  // namespace

void print_usage() { std::printf(kUsage, scene_list().c_str()); }

int command(int argc, char** argv) {
  if (argc < 2) throw UsageError("no command given");
  const std::string cmd = argv[1];
  if (cmd == "--help" || cmd == "-h" || cmd == "help") {
    print_usage();
    return 0;
  }
  if (cmd == "run") return cmd_run(argc - 2, argv + 2);
  if (cmd == "validate") return cmd_validate(argc - 2, argv + 2);
  throw UsageError("unknown command '" + cmd + "'");
}

}  // namespace huygens

// MPI (comm.hpp) starts inside run_program's body (after its one re-execution) and ends with the
// body; an error that escapes the body on one rank of several ends them all by MPI_Abort with the
// program's exit code, after run_program printed the message (comm::exit_code). Agreed stops (a
// non-finite value, a negative depth, a signal: reduced at step boundaries) end every rank
// cleanly with the same code.
int main(int argc, char** argv) {
  using namespace huygens;
  const int rc = run_program("huygens", argv, [&]() {
    comm::init(&argc, &argv);
    const int code = command(argc, argv);
    comm::finalize();
    return code;
  });
  return comm::exit_code(rc);
}
