// qf-bake entry point: the command table (commands.cpp) as a program (cli/program.h), which maps
// errors to exit codes (0 ok, 1 bad input, 2 bad usage, 3 internal error, 4 output not written,
// 5 output folder busy).
#include "cli/commands.h"
#include "cli/program.h"

namespace {

// `qf-bake IN -o OUTDIR` is `qf-bake bake IN -o OUTDIR`: a first argument that looks like a file.
bool names_a_file(const std::string& a) { return a.find('.') != std::string::npos && a[0] != '-'; }

}  // namespace

constexpr const char* kUsage =
    "usage: qf-bake IN -o OUTDIR [options]   bake (the main job; see qf-bake bake --help)\n"
    "       qf-bake COMMAND [arguments] [options]\n"
    "       qf-bake COMMAND --help      options of one command, with their defaults\n"
    "       qf-bake --version\n";
constexpr const char* kExitCodes =
    "exit codes: 0 ok, 1 bad input (the message names the file, the line or byte, and what was\n"
    "expected), 2 bad usage (an output path naming a missing folder included), 3 internal error,\n"
    "4 an output that cannot be written (disk or quota full, read-only, no permission, I/O error),\n"
    "5 the output folder is being written by another bake now (nothing written; retry later).\n"
    "A batch exits 1 when an asset failed; each asset's own code is in its report.\n";

int main(int argc, char** argv) {
  const qf::cli::Program program{"qf-bake", "extreme simplification of point sets and meshes into textured quads", kUsage, kExitCodes,
                                 qf::cli::commands(), 17, "bake", names_a_file};
  return qf::cli::run_program(program, argc, argv);
}
